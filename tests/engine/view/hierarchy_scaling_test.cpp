// Placing the mesh nodes of a deep hierarchy is one pass over it (issue 37):
// walking to the root for every node made a chain of nodes O(n^2) (a 589 KB
// chain never rendered). Work is counted (tests/common/work_scaling.h).
#include "engine/view/scene_mesh_nodes.h"

#include <vector>

#include <gtest/gtest.h>

#include "tests/common/test_meshes.h"
#include "tests/common/work_scaling.h"

namespace {

// A chain of n nodes, each one unit above its parent and drawing the sheet.
eng::Model chainOf(size_t n) {
  eng::Mesh mesh;
  mesh.primitives.push_back(testing_support::flatSheet(2));
  eng::Model model = testing_support::singleMeshModel(mesh);
  model.nodes.resize(n);
  for (size_t i = 0; i < n; ++i) {
    model.nodes[i].mesh = 0;
    model.nodes[i].translation = glm::vec3(0, 1, 0);
    model.nodes[i].parent = int(i) - 1;
    if (i + 1 < n) model.nodes[i].children = {int(i + 1)};
  }
  return model;
}

TEST(HierarchyScaling, SceneMeshNodesOfAChainAreLinear) {
  testing_support::expectLinearWork([](size_t n) {
    const eng::Model model = chainOf(n);
    const std::vector<eng::MeshNode> nodes = eng::sceneMeshNodes(model);
    ASSERT_EQ(nodes.size(), n);
    EXPECT_EQ(nodes.back().world[3].y, float(n)) << "the last node stands n units up";
  }, 2000);
}

}  // namespace
