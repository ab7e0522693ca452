#include "autorig/posed_face.h"

#include <gtest/gtest.h>

#include "tests/common/test_meshes.h"

namespace {

// A node translated and scaled: world positions follow the node, and a world
// delta taken back to mesh space undoes the node's scale.
TEST(PosedFace, PlacesPrimitivesInWorldSpaceAndTakesDeltasBack) {
  eng::Model model = testing_support::singleMeshModel(eng::Mesh{.name = "sheet", .primitives = {testing_support::flatSheet(3)}});
  ASSERT_FALSE(model.nodes.empty());
  model.nodes[0].translation = {1.0f, 2.0f, 3.0f};
  model.nodes[0].scale = glm::vec3(2.0f);
  autorig::PosedFace posed = autorig::poseAtRest(model);
  ASSERT_EQ(posed.primitives.size(), 1u);
  const autorig::PosedPrimitive& p = posed.primitives[0];
  const glm::vec3 rest = model.meshes[0].primitives[0].positions[0];
  EXPECT_NEAR(p.positions[0].x, rest.x * 2.0f + 1.0f, 1e-5f);
  EXPECT_NEAR(p.positions[0].y, rest.y * 2.0f + 2.0f, 1e-5f);
  glm::vec3 local = p.toLocal(0, {0.2f, 0.0f, 0.0f});
  EXPECT_NEAR(local.x, 0.1f, 1e-6f);
  EXPECT_EQ(posed.find(0, 0), &p);
  EXPECT_EQ(posed.find(0, 1), nullptr);
  EXPECT_EQ(posed.vertexCount(), model.meshes[0].primitives[0].vertexCount());
}

}  // namespace
