#include "engine/scene/posed_bounds.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/scene/skinning.h"
#include "engine/scene/weights.h"

namespace eng {
namespace {

// Calls visit(world position, primitive, vertex, mesh node, skin index or -1)
// for every posed vertex of the default scene.
template <class Visit>
void forEachPosedVertex(const Model& model, const Pose& pose, std::span<const float> weights, Visit&& visit) {
  std::vector<glm::mat4> world;
  poseWorldMatrices(model, pose, world);
  const WeightLayout layout(model);
  const bool morph = !weights.empty() && weights.size() == layout.total();
  std::vector<float> zeros;
  std::vector<glm::vec3> positions;
  for (const int n : sceneMeshNodeIndices(model)) {
    const Node& node = model.nodes[n];
    const int skin = node.skin >= 0 && static_cast<size_t>(node.skin) < model.skins.size() ? node.skin : -1;
    zeros.assign(layout.count(node.mesh), 0.0f);
    const std::span<const float> meshWeights = morph ? *layout.meshWeights(weights, node.mesh) : std::span<const float>(zeros);
    for (const Primitive& prim : model.meshes[node.mesh].primitives) {
      positions.resize(prim.vertexCount());
      posePrimitiveCpu(model, n, prim, meshWeights, world, positions, {});
      for (size_t v = 0; v < positions.size(); ++v)
        visit(glm::vec3(world[n] * glm::vec4(positions[v], 1.0f)), prim, v, n, skin);
    }
  }
}

// "mixamorig:Head" -> "head", "J_Bip_C_Head" -> "head", "Bip01 Head" -> "head".
std::string lastNameWord(std::string_view name) {
  const size_t cut = name.find_last_of(":_ .|");
  if (cut != std::string_view::npos) name.remove_prefix(cut + 1);
  std::string out;
  for (char c : name) out.push_back(char(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

}  // namespace

Aabb posedBounds(const Model& model, const Pose& pose, std::span<const float> weights) {
  Aabb box;
  forEachPosedVertex(model, pose, weights, [&](const glm::vec3& p, const Primitive&, size_t, int, int) { box.extend(p); });
  return box;
}

Aabb posedJointRegionBounds(const Model& model, const Pose& pose, int joint, float minWeight,
                            std::span<const float> weights) {
  Aabb box;
  if (joint < 0 || static_cast<size_t>(joint) >= model.nodes.size()) return box;
  // The joint and every node under it.
  std::vector<bool> inRegion(model.nodes.size(), false);
  std::vector<int> stack{joint};
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (n < 0 || static_cast<size_t>(n) >= model.nodes.size() || inRegion[n]) continue;
    inRegion[n] = true;
    for (int c : model.nodes[n].children) stack.push_back(c);
  }
  // Per skin: which of its joint slots lie in the region.
  std::vector<std::vector<bool>> slotInRegion(model.skins.size());
  for (size_t s = 0; s < model.skins.size(); ++s)
    for (int node : model.skins[s].joints)
      slotInRegion[s].push_back(node >= 0 && static_cast<size_t>(node) < inRegion.size() && inRegion[node]);
  forEachPosedVertex(model, pose, weights, [&](const glm::vec3& p, const Primitive& prim, size_t v, int node, int skin) {
    if (skin < 0 || prim.influenceSets() == 0) {
      // Rigid meshes hung under the joint (a robot's head, glasses) move with it whole.
      if (inRegion[node]) box.extend(p);
      return;
    }
    const size_t sets = prim.influenceSets();
    float w = 0.0f;
    for (size_t s = 0; s < sets; ++s)
      for (int i = 0; i < 4; ++i) {
        const size_t slot = prim.joints[v * sets + s][i];
        if (slot < slotInRegion[skin].size() && slotInRegion[skin][slot]) w += prim.jointWeights[v * sets + s][i];
      }
    if (w >= minWeight) box.extend(p);
  });
  return box;
}

Aabb posedMorphedBounds(const Model& model, const Pose& pose) {
  // Which vertices of each primitive some target moves, found once per primitive.
  std::unordered_map<const Primitive*, std::vector<bool>> moved;
  auto movedOf = [&](const Primitive& prim) -> const std::vector<bool>& {
    auto [it, fresh] = moved.try_emplace(&prim);
    if (!fresh) return it->second;
    const size_t n = prim.positions.size();
    it->second.assign(n, false);
    Aabb local;
    for (const glm::vec3& p : prim.positions) local.extend(p);
    const float noise = std::max(local.diagonal() * 1e-3f, 1e-12f);
    for (const MorphTarget& target : prim.targets) {
      if (target.positions.size() != n) continue;
      // What a target carries, not the skin it drags along with it: a brow
      // raise also nudges the scalp, a jaw drop the neck.
      float largest = 0.0f;
      for (const glm::vec3& d : target.positions) largest = std::max(largest, glm::length(d));
      const float threshold = std::max(noise, 0.1f * largest);
      for (size_t v = 0; v < n; ++v)
        if (glm::length(target.positions[v]) > threshold) it->second[v] = true;
    }
    return it->second;
  };
  Aabb box;
  forEachPosedVertex(model, pose, {}, [&](const glm::vec3& p, const Primitive& prim, size_t v, int, int) {
    if (prim.targets.empty()) return;
    const std::vector<bool>& m = movedOf(prim);
    if (v < m.size() && m[v]) box.extend(p);
  });
  return box;
}

int findHeadJoint(const Model& model) {
  if (model.skins.empty()) return -1;
  if (model.humanoidHead >= 0 && static_cast<size_t>(model.humanoidHead) < model.nodes.size()) return model.humanoidHead;
  for (const Skin& skin : model.skins)
    for (int node : skin.joints)
      if (node >= 0 && static_cast<size_t>(node) < model.nodes.size() && lastNameWord(model.nodes[node].name) == "head")
        return node;
  // No names to go by: the highest joint that moves vertices itself, or the
  // one it hangs from when that one moves more of them around it. An eye's
  // joint sits higher than the head's (Ready Player Me: LeftEye, RightEye),
  // and framing it shows one eyeball.
  const Pose pose = restPose(model);
  std::vector<size_t> moves(model.nodes.size(), 0);  // vertices each joint carries most of
  std::vector<Aabb> region(model.nodes.size());
  forEachPosedVertex(model, pose, {}, [&](const glm::vec3& p, const Primitive& prim, size_t v, int, int skin) {
    if (skin < 0) return;
    const size_t sets = prim.influenceSets();
    for (size_t s = 0; s < sets; ++s)
      for (int k = 0; k < 4; ++k) {
        const size_t slot = prim.joints[v * sets + s][k];
        if (prim.jointWeights[v * sets + s][k] < 0.5f || slot >= model.skins[skin].joints.size()) continue;
        const int j = model.skins[skin].joints[slot];
        if (j >= 0 && static_cast<size_t>(j) < moves.size()) ++moves[j], region[j].extend(p);
      }
  });
  std::vector<glm::mat4> world;
  poseWorldMatrices(model, pose, world);
  std::vector<int> parent(model.nodes.size(), -1);
  for (size_t n = 0; n < model.nodes.size(); ++n)
    for (int c : model.nodes[n].children)
      if (c >= 0 && static_cast<size_t>(c) < parent.size()) parent[c] = static_cast<int>(n);
  int best = -1;
  for (size_t n = 0; n < model.nodes.size(); ++n)
    if (moves[n] > 0 && (best < 0 || world[n][3].y > world[best][3].y)) best = static_cast<int>(n);
  for (size_t steps = 0; best >= 0 && steps < model.nodes.size(); ++steps) {
    int up = parent[best];
    while (up >= 0 && moves[up] == 0) up = parent[up];
    if (up < 0 || moves[up] <= moves[best]) break;
    const glm::vec3 c = region[best].center();
    if (glm::any(glm::lessThan(c, region[up].min)) || glm::any(glm::greaterThan(c, region[up].max))) break;
    best = up;
  }
  return best;
}

}  // namespace eng
