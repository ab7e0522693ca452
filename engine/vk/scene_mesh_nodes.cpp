#include "engine/vk/scene_mesh_nodes.h"

namespace eng::vk {

std::vector<MeshNode> sceneMeshNodes(const Model& model) {
  std::vector<MeshNode> out;
  std::vector<int> stack(model.roots.rbegin(), model.roots.rend());
  std::vector<bool> seen(model.nodes.size(), false);
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (n < 0 || n >= static_cast<int>(model.nodes.size()) || seen[static_cast<size_t>(n)]) continue;
    seen[static_cast<size_t>(n)] = true;  // shared children and cycles: once
    const Node& node = model.nodes[static_cast<size_t>(n)];
    if (node.mesh >= 0 && node.mesh < static_cast<int>(model.meshes.size()))
      out.push_back({n, node.mesh, model.worldTransform(n), node.skin});
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
  }
  return out;
}

}  // namespace eng::vk
