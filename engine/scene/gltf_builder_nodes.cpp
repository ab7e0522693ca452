// The glTF node hierarchy and animations (morph weights and node transforms).
#include "engine/scene/gltf_model_builder.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "engine/scene/gltf_skin_reader.h"

namespace eng {

Result<void> GltfModelBuilder::loadNodes() {
  const size_t count = gltf_.nodes.size();
  model_.nodes.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const tinygltf::Node& src = gltf_.nodes[i];
    Node& node = model_.nodes[i];
    const std::string label = "node " + std::to_string(i) + (src.name.empty() ? "" : " '" + src.name + "'");
    node.name = src.name;
    if (src.mesh >= 0 && static_cast<size_t>(src.mesh) >= model_.meshes.size())
      return fail(label + " refers to mesh " + std::to_string(src.mesh) + ", the file has " +
                  std::to_string(model_.meshes.size()));
    node.mesh = src.mesh;
    bool finite = true;
    auto num = [&](double v) {
      finite = finite && std::isfinite(v);
      return static_cast<float>(v);
    };
    if (src.matrix.size() == 16) {
      node.hasMatrix = true;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) node.matrix[c][r] = num(src.matrix[c * 4 + r]);  // column-major, like glm
    } else {
      if (src.translation.size() == 3)
        node.translation = glm::vec3(num(src.translation[0]), num(src.translation[1]), num(src.translation[2]));
      if (src.rotation.size() == 4)
        node.rotation = glm::quat(num(src.rotation[3]), num(src.rotation[0]), num(src.rotation[1]), num(src.rotation[2]));
      if (src.scale.size() == 3) node.scale = glm::vec3(num(src.scale[0]), num(src.scale[1]), num(src.scale[2]));
    }
    if (!finite) return fail(label + " has a non-finite transform");
    for (int child : src.children) {
      if (child < 0 || static_cast<size_t>(child) >= count)
        return fail(label + " has child " + std::to_string(child) + ", the file has " + std::to_string(count) + " nodes");
      if (static_cast<size_t>(child) == i) return fail(label + " is its own child");
      node.children.push_back(child);
    }
  }
  for (size_t i = 0; i < count; ++i)
    for (int child : model_.nodes[i].children) {
      Node& c = model_.nodes[child];
      if (c.parent >= 0)
        return fail("node " + std::to_string(child) + " has two parents (nodes " + std::to_string(c.parent) + " and " +
                    std::to_string(i) + ")");
      c.parent = static_cast<int>(i);
    }
  // Every node has at most one parent, so a cycle shows up as a walk up
  // the parents that meets itself. Each node is walked once: O(nodes).
  std::vector<int> walkOf(count, -1);  // which walk visited the node, -1 none
  for (int i = 0; i < static_cast<int>(count); ++i) {
    for (int n = i; n >= 0; n = model_.nodes[n].parent) {
      if (walkOf[n] == i) return fail("the node hierarchy has a cycle through node " + std::to_string(n));
      if (walkOf[n] >= 0) break;  // joins an earlier walk, which ended at a root
      walkOf[n] = i;
    }
  }

  int scene = gltf_.defaultScene;
  if (scene >= static_cast<int>(gltf_.scenes.size())) {
    warn("default scene " + std::to_string(scene) + " does not exist; first scene used");
    scene = -1;
  }
  if (scene < 0 && !gltf_.scenes.empty()) scene = 0;
  if (scene >= 0) {
    for (int root : gltf_.scenes[scene].nodes) {
      if (root < 0 || static_cast<size_t>(root) >= count) {
        warn("scene " + std::to_string(scene) + " lists node " + std::to_string(root) + ", which does not exist; ignored");
        continue;
      }
      if (model_.nodes[root].parent >= 0) {
        warn("scene " + std::to_string(scene) + " lists node " + std::to_string(root) + ", which has a parent; ignored");
        continue;
      }
      model_.roots.push_back(root);
    }
  } else {
    for (size_t i = 0; i < count; ++i)
      if (model_.nodes[i].parent < 0) model_.roots.push_back(static_cast<int>(i));
  }
  if (model_.roots.empty() && !model_.meshes.empty()) warn("no scene node shows any mesh; nothing would be drawn");
  return {};
}

Result<void> GltfModelBuilder::loadAnimations() {
  for (size_t a = 0; a < gltf_.animations.size(); ++a) {
    const tinygltf::Animation& src = gltf_.animations[a];
    Animation anim;
    anim.name = src.name.empty() ? "animation_" + std::to_string(a) : src.name;
    for (size_t c = 0; c < src.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = src.channels[c];
      const std::string label = "animation '" + anim.name + "' channel " + std::to_string(c);
      if (ch.target_path != "weights") {
        ++anim.otherChannelCount;
        if (auto ok = readNodeChannel(reader_, src, c, label, model_, anim); !ok) return fail(ok.error());
        continue;
      }
      if (ch.target_node < 0 || static_cast<size_t>(ch.target_node) >= model_.nodes.size() ||
          model_.nodes[ch.target_node].mesh < 0) {
        warn(label + " animates the weights of node " + std::to_string(ch.target_node) + ", which has no mesh; skipped");
        continue;
      }
      if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= src.samplers.size()) {
        warn(label + " uses sampler " + std::to_string(ch.sampler) + ", the animation has " +
             std::to_string(src.samplers.size()) + "; skipped");
        continue;
      }
      const tinygltf::AnimationSampler& sampler = src.samplers[ch.sampler];
      WeightsChannel out;
      out.node = ch.target_node;
      out.mesh = model_.nodes[ch.target_node].mesh;
      out.targetCount = model_.meshes[out.mesh].targetNames.size();
      if (sampler.interpolation == "STEP") out.interpolation = Interpolation::Step;
      else if (sampler.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
      else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
      else {
        warn(label + " has unknown interpolation '" + sampler.interpolation + "'; LINEAR used");
      }
      auto times = reader_.readScalars(sampler.input, label + " input");
      if (!times) return fail(times.error());
      auto values = reader_.readScalars(sampler.output, label + " output");
      if (!values) return fail(values.error());
      const size_t perKey = out.targetCount * (out.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (values->size() != times->size() * perKey) {
        warn(label + ": output has " + std::to_string(values->size()) + " values, expected " +
             std::to_string(times->size() * perKey) + " (" + std::to_string(times->size()) + " keys x " +
             std::to_string(perKey) + "); skipped");
        continue;
      }
      if (!std::is_sorted(times->begin(), times->end())) {
        warn(label + ": key times are not increasing; skipped");
        continue;
      }
      out.times = std::move(*times);
      out.values = std::move(*values);
      anim.channels.push_back(std::move(out));
    }
    model_.animations.push_back(std::move(anim));
  }
  return {};
}

}  // namespace eng
