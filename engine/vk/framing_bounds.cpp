#include "engine/vk/framing_bounds.h"

#include "engine/vk/scene_mesh_nodes.h"

namespace eng::vk {

Aabb framingBounds(const Model& model) {
  Aabb box;
  for (const MeshNode& node : sceneMeshNodes(model)) {
    for (const Primitive& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives) {
      const size_t n = prim.positions.size();
      auto extend = [&](const glm::vec3& p) { box.extend(glm::vec3(node.world * glm::vec4(p, 1.0f))); };
      for (const glm::vec3& p : prim.positions) extend(p);
      for (const MorphTarget& target : prim.targets) {
        if (target.positions.size() != n) continue;  // no position deltas (or inconsistent: GpuModel rejects it)
        for (size_t v = 0; v < n; ++v) extend(prim.positions[v] + target.positions[v]);
      }
    }
  }
  return box;
}

}  // namespace eng::vk
