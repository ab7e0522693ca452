// Model helpers: node transforms, world bounds, counts, animation duration.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/model.h"

namespace {

TEST(Model, LocalTransformAppliesScaleThenRotationThenTranslation) {
  eng::Node n;
  n.translation = {1, 0, 0};
  n.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  n.scale = {2, 2, 2};
  const glm::vec3 p = glm::vec3(n.localTransform() * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(p.x, 1.0f, 1e-6f);  // (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,2,0)
  EXPECT_NEAR(p.y, 2.0f, 1e-6f);
  n.hasMatrix = true;
  n.matrix = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 7));
  EXPECT_EQ(n.localTransform(), n.matrix);
}

TEST(Model, WorldTransformAndBoundsFollowTheHierarchy) {
  eng::Model model;
  eng::Mesh mesh;
  mesh.primitives.push_back(eng::Primitive{.positions = {{-1, -1, 0}, {1, 1, 0}}});
  model.meshes.push_back(mesh);
  eng::Node parent, child, hidden;
  parent.translation = {10, 0, 0};
  parent.children = {1};
  child.parent = 0;
  child.scale = {2, 2, 2};
  child.mesh = 0;
  hidden.mesh = 0;  // not reachable from the roots: not drawn, not in the bounds
  hidden.translation = {1000, 0, 0};
  model.nodes = {parent, child, hidden};
  model.roots = {0};
  const glm::vec3 p = glm::vec3(model.worldTransform(1) * glm::vec4(1, 1, 0, 1));
  EXPECT_EQ(p, glm::vec3(12, 2, 0));
  const eng::Aabb box = model.bounds();
  ASSERT_TRUE(box.valid());
  EXPECT_EQ(box.min, glm::vec3(8, -2, 0));
  EXPECT_EQ(box.max, glm::vec3(12, 2, 0));
  EXPECT_EQ(model.totalVertexCount(), 2u);
}

TEST(Model, EmptyModelHasInvalidBounds) {
  EXPECT_FALSE(eng::Model{}.bounds().valid());
  EXPECT_EQ(eng::Model{}.totalVertexCount(), 0u);
}

TEST(Model, AnimationDurationIsTheLastKeyOfAnyChannel) {
  eng::Animation anim;
  EXPECT_EQ(anim.duration(), 0.0f);
  anim.channels.push_back(eng::WeightsChannel{.times = {0.0f, 1.5f}});
  anim.channels.push_back(eng::WeightsChannel{.times = {0.2f, 2.5f}});
  EXPECT_EQ(anim.duration(), 2.5f);
}

}  // namespace
