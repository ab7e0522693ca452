#include "engine/view/scene_mesh_nodes.h"

#include "engine/scene/skeleton_pose.h"

namespace eng {

std::vector<MeshNode> sceneMeshNodes(const Model& model) {
  std::vector<MeshNode> out;
  for (const int n : sceneMeshNodeIndices(model)) {
    const Node& node = model.nodes[static_cast<size_t>(n)];
    out.push_back({n, node.mesh, model.worldTransform(n), node.skin});
  }
  return out;
}

}  // namespace eng
