#include "engine/view/scene_mesh_nodes.h"

#include "engine/scene/skeleton_pose.h"

namespace eng {

std::vector<MeshNode> sceneMeshNodes(const Model& model) {
  std::vector<MeshNode> out;
  const std::vector<glm::mat4> world = restWorldMatrices(model);
  for (const int n : sceneMeshNodeIndices(model)) {
    const Node& node = model.nodes[static_cast<size_t>(n)];
    out.push_back({n, node.mesh, world[static_cast<size_t>(n)], node.skin});
  }
  return out;
}

}  // namespace eng
