#include "engine/scene/gltf_skin_reader.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/work_counter.h"

namespace eng {
namespace {

std::string skinLabel(const tinygltf::Model& gltf, size_t s) {
  const std::string& name = gltf.skins[s].name;
  return "skin " + std::to_string(s) + (name.empty() ? "" : " '" + name + "'");
}

// VRMC_vrm 1.0: humanoid.humanBones.head.node; VRM 0.x: humanoid.humanBones[] {bone: "head", node}.
int vrmHumanoidHead(const tinygltf::Model& gltf) {
  auto nodeOf = [&](const tinygltf::Value& v) {
    if (!v.IsObject() || !v.Has("node") || !v.Get("node").IsNumber()) return -1;
    const int node = v.Get("node").GetNumberAsInt();
    return node >= 0 && static_cast<size_t>(node) < gltf.nodes.size() ? node : -1;
  };
  if (const auto it = gltf.extensions.find("VRMC_vrm"); it != gltf.extensions.end()) {
    const tinygltf::Value& vrm = it->second;
    if (vrm.IsObject() && vrm.Has("humanoid")) {
      const tinygltf::Value& bones = vrm.Get("humanoid").Get("humanBones");
      if (bones.IsObject() && bones.Has("head")) return nodeOf(bones.Get("head"));
    }
  }
  if (const auto it = gltf.extensions.find("VRM"); it != gltf.extensions.end()) {
    const tinygltf::Value& vrm = it->second;
    if (vrm.IsObject() && vrm.Has("humanoid")) {
      const tinygltf::Value& bones = vrm.Get("humanoid").Get("humanBones");
      for (size_t i = 0; bones.IsArray() && i < bones.ArrayLen(); ++i) {
        const tinygltf::Value& bone = bones.Get(static_cast<int>(i));
        if (bone.IsObject() && bone.Has("bone") && bone.Get("bone").IsString() &&
            bone.Get("bone").Get<std::string>() == "head")
          return nodeOf(bone);
      }
    }
  }
  return -1;
}

// Why `skin` cannot deform the primitives of `mesh`, or "" when it can.
std::string jointRangeProblem(const Mesh& mesh, const Skin& skin) {
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const Primitive& prim = mesh.primitives[p];
    countWork(prim.joints.size());
    for (size_t i = 0; i < prim.joints.size(); ++i)
      for (int k = 0; k < 4; ++k)
        if (prim.jointWeights[i][k] > 0.0f && prim.joints[i][k] >= skin.joints.size())
          return "primitive " + std::to_string(p) + " vertex " + std::to_string(i / prim.influenceSets()) +
                 " uses joint " + std::to_string(prim.joints[i][k]) + ", the skin has " +
                 std::to_string(skin.joints.size());
  }
  return "";
}

}  // namespace

Result<void> readSkinAttributes(GltfAccessorReader& reader, const tinygltf::Model& gltf, const tinygltf::Primitive& src,
                                const std::string& label, Primitive& out, std::vector<std::string>& warnings) {
  const size_t n = out.positions.size();
  std::vector<std::vector<glm::vec4>> joints, weights;
  for (int set = 0;; ++set) {
    const std::string suffix = "_" + std::to_string(set);
    const auto j = src.attributes.find("JOINTS" + suffix);
    const auto w = src.attributes.find("WEIGHTS" + suffix);
    if (j == src.attributes.end() && w == src.attributes.end()) break;
    if (j == src.attributes.end() || w == src.attributes.end()) {
      warnings.push_back(label + " has " + (j == src.attributes.end() ? "WEIGHTS" : "JOINTS") + suffix +
                         " without its pair; ignored from there on");
      break;
    }
    const std::string jointsWhat = label + " JOINTS" + suffix, weightsWhat = label + " WEIGHTS" + suffix;
    if (auto count = reader.count(j->second, jointsWhat); !count) return count.error();
    if (auto count = reader.count(w->second, weightsWhat); !count) return count.error();
    const tinygltf::Accessor& ja = gltf.accessors[j->second];
    const tinygltf::Accessor& wa = gltf.accessors[w->second];
    if (ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
      return makeError(ErrorKind::Malformed, jointsWhat + " has componentType " + std::to_string(ja.componentType) +
                       ", glTF allows UNSIGNED_BYTE (5121) or UNSIGNED_SHORT (5123)");
    const bool floatWeights = wa.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool unormWeights = (wa.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               wa.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) &&
                              wa.normalized;
    if (!floatWeights && !unormWeights)
      return makeError(ErrorKind::Malformed, weightsWhat + " has componentType " + std::to_string(wa.componentType) +
                       (wa.normalized ? "" : " (not normalized)") +
                       ", glTF allows FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT");
    auto jv = reader.readVec<4>(j->second, jointsWhat);
    if (!jv) return jv.error();
    auto wv = reader.readVec<4>(w->second, weightsWhat);
    if (!wv) return wv.error();
    if (jv->size() != n || wv->size() != n)
      return makeError(ErrorKind::Malformed, label + " JOINTS" + suffix + " / WEIGHTS" + suffix + " have " + std::to_string(jv->size()) +
                       " / " + std::to_string(wv->size()) + " elements, its primitive has " + std::to_string(n) +
                       " vertices");
    joints.push_back(std::move(*jv));
    weights.push_back(std::move(*wv));
  }
  if (joints.empty()) return {};

  const size_t sets = joints.size();
  out.joints.resize(n * sets);
  out.jointWeights.resize(n * sets);
  size_t unweighted = 0;
  for (size_t v = 0; v < n; ++v) {
    float sum = 0.0f;
    for (size_t s = 0; s < sets; ++s) {
      out.joints[v * sets + s] = glm::u16vec4(joints[s][v]);
      const glm::vec4 w = glm::max(weights[s][v], glm::vec4(0.0f));  // negative weights are invalid: no influence
      out.jointWeights[v * sets + s] = w;
      sum += w.x + w.y + w.z + w.w;
    }
    // Exporters round (RobotExpressive's sums are off by more than the spec's
    // tolerance); three.js and Filament renormalise too.
    if (sum > 0.0f)
      for (size_t s = 0; s < sets; ++s) out.jointWeights[v * sets + s] /= sum;
    else
      ++unweighted;
  }
  if (unweighted > 0)
    warnings.push_back(label + ": " + std::to_string(unweighted) + " vertices have no joint weight; they stay in the bind pose");
  return {};
}

Result<void> readSkins(GltfAccessorReader& reader, const tinygltf::Model& gltf, Model& model) {
  model.humanoidHead = vrmHumanoidHead(gltf);
  std::vector<bool> usable(gltf.skins.size(), true);
  for (size_t s = 0; s < gltf.skins.size(); ++s) {
    const tinygltf::Skin& src = gltf.skins[s];
    const std::string label = skinLabel(gltf, s);
    Skin skin;
    skin.name = src.name;
    skin.skeleton = src.skeleton >= 0 && static_cast<size_t>(src.skeleton) < model.nodes.size() ? src.skeleton : -1;
    std::string problem;
    for (int joint : src.joints) {
      if (joint < 0 || static_cast<size_t>(joint) >= model.nodes.size()) {
        problem = "joint node " + std::to_string(joint) + " does not exist (the file has " +
                  std::to_string(model.nodes.size()) + " nodes)";
        break;
      }
      skin.joints.push_back(joint);
    }
    if (problem.empty() && src.joints.empty()) problem = "has no joints";
    if (problem.empty() && src.inverseBindMatrices >= 0) {
      auto count = reader.count(src.inverseBindMatrices, label + " inverseBindMatrices");
      if (!count) {
        problem = count.error().message;
      } else if (gltf.accessors[src.inverseBindMatrices].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        problem = "inverseBindMatrices must be FLOAT";
      } else if (*count != skin.joints.size()) {
        problem = "has " + std::to_string(*count) + " inverse bind matrices for " + std::to_string(skin.joints.size()) +
                  " joints";
      } else if (auto flat = reader.readFloats(src.inverseBindMatrices, 16, label + " inverseBindMatrices"); !flat) {
        problem = flat.error().message;
      } else {
        skin.inverseBindMatrices.resize(skin.joints.size());
        for (size_t j = 0; j < skin.joints.size(); ++j)
          for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) skin.inverseBindMatrices[j][c][r] = (*flat)[j * 16 + c * 4 + r];
      }
    } else if (problem.empty()) {
      skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));  // glTF: identity when absent
    }
    if (!problem.empty()) {
      model.warnings.push_back(label + ": " + problem + "; the skin is dropped and its meshes drawn unskinned");
      usable[s] = false;
      skin.joints.clear();
      skin.inverseBindMatrices.clear();
    }
    model.skins.push_back(std::move(skin));
  }

  std::map<std::pair<int, int>, std::string> jointProblems;  // (mesh, skin) -> jointRangeProblem
  for (size_t i = 0; i < gltf.nodes.size() && i < model.nodes.size(); ++i) {
    const int s = gltf.nodes[i].skin;
    if (s < 0) continue;
    const std::string label = "node " + std::to_string(i) + (gltf.nodes[i].name.empty() ? "" : " '" + gltf.nodes[i].name + "'");
    if (static_cast<size_t>(s) >= gltf.skins.size()) {
      model.warnings.push_back(label + " refers to skin " + std::to_string(s) + ", the file has " +
                               std::to_string(gltf.skins.size()) + "; drawn unskinned");
      continue;
    }
    if (!usable[s]) continue;
    Node& node = model.nodes[i];
    if (node.mesh < 0) continue;  // a skin without a mesh deforms nothing
    // Many nodes may draw one skinned mesh: each pair is checked once, not once a node (nodes x vertices).
    const auto [pair, fresh] = jointProblems.try_emplace({node.mesh, s});
    if (fresh) pair->second = jointRangeProblem(model.meshes[node.mesh], model.skins[s]);
    if (const std::string& problem = pair->second; !problem.empty()) {
      model.warnings.push_back(label + ": mesh " + std::to_string(node.mesh) + " " + problem + "; drawn unskinned");
      continue;
    }
    node.skin = s;
  }
  return {};
}

Result<void> readNodeChannel(GltfAccessorReader& reader, const tinygltf::Animation& src, size_t c,
                             const std::string& label, Model& model, Animation& anim) {
  const tinygltf::AnimationChannel& ch = src.channels[c];
  NodeChannel out;
  if (ch.target_path == "translation") out.path = NodePath::Translation;
  else if (ch.target_path == "rotation") out.path = NodePath::Rotation;
  else if (ch.target_path == "scale") out.path = NodePath::Scale;
  else {
    model.warnings.push_back(label + " animates '" + ch.target_path + "', which is not supported; skipped");
    return {};
  }
  if (ch.target_node < 0 || static_cast<size_t>(ch.target_node) >= model.nodes.size()) {
    model.warnings.push_back(label + " animates node " + std::to_string(ch.target_node) + ", the file has " +
                             std::to_string(model.nodes.size()) + "; skipped");
    return {};
  }
  if (model.nodes[ch.target_node].hasMatrix) {
    model.warnings.push_back(label + " animates node " + std::to_string(ch.target_node) +
                             ", which has a matrix (glTF forbids animating it); skipped");
    return {};
  }
  if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= src.samplers.size()) {
    model.warnings.push_back(label + " uses sampler " + std::to_string(ch.sampler) + ", the animation has " +
                             std::to_string(src.samplers.size()) + "; skipped");
    return {};
  }
  const tinygltf::AnimationSampler& sampler = src.samplers[ch.sampler];
  out.node = ch.target_node;
  if (sampler.interpolation == "STEP") out.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
  else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
  else model.warnings.push_back(label + " has unknown interpolation '" + sampler.interpolation + "'; LINEAR used");
  auto times = reader.readScalars(sampler.input, label + " input");
  if (!times) return times.error();
  auto values = reader.readFloats(sampler.output, static_cast<int>(out.components()), label + " output");
  if (!values) return values.error();
  const size_t perKey = out.components() * (out.interpolation == Interpolation::CubicSpline ? 3 : 1);
  if (times->empty() || values->size() != times->size() * perKey) {
    model.warnings.push_back(label + ": output has " + std::to_string(values->size()) + " values, expected " +
                             std::to_string(times->size() * perKey) + " (" + std::to_string(times->size()) +
                             " keys x " + std::to_string(perKey) + "); skipped");
    return {};
  }
  if (!std::is_sorted(times->begin(), times->end())) {
    model.warnings.push_back(label + ": key times are not increasing; skipped");
    return {};
  }
  if (out.path == NodePath::Rotation && out.interpolation != Interpolation::CubicSpline) {
    // Keys are unit quaternions by the spec; quantised ones are only close, and slerp needs unit length.
    for (size_t k = 0; k < times->size(); ++k) {
      float* q = values->data() + k * 4;
      const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (len > 0.0f)
        for (int i = 0; i < 4; ++i) q[i] /= len;
    }
  }
  out.times = std::move(*times);
  out.values = std::move(*values);
  anim.nodeChannels.push_back(std::move(out));
  return {};
}

}  // namespace eng
