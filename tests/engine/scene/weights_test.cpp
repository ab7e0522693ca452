// WeightLayout: one flat, mesh-major weight vector per model.
#include <gtest/gtest.h>

#include "engine/scene/weights.h"

namespace {

eng::Model threeMeshes() {
  eng::Model model;
  eng::Mesh a, none, c;
  a.targetNames = {"smile", "blink"};
  a.defaultWeights = {0.1f, 0.2f};
  c.targetNames = {"blink", "jawOpen", "frown"};
  c.defaultWeights = {0.0f, 0.5f, 0.0f};
  model.meshes = {a, none, c};
  return model;
}

TEST(WeightLayout, OffsetsAreMeshMajor) {
  const eng::WeightLayout layout(threeMeshes());
  EXPECT_EQ(layout.meshCount(), 3);
  EXPECT_EQ(layout.offset(0), 0u);
  EXPECT_EQ(layout.offset(1), 2u);
  EXPECT_EQ(layout.offset(2), 2u);
  EXPECT_EQ(layout.offset(3), 5u);
  EXPECT_EQ(layout.count(1), 0u);
  EXPECT_EQ(layout.count(2), 3u);
  EXPECT_EQ(layout.total(), 5u);
  EXPECT_EQ(layout.names(), (std::vector<std::string>{"smile", "blink", "blink", "jawOpen", "frown"}));
  EXPECT_EQ(layout.defaults(), (std::vector<float>{0.1f, 0.2f, 0.0f, 0.5f, 0.0f}));
}

TEST(WeightLayout, SetByNameSetsTheTargetOnEveryMeshThatHasIt) {
  const eng::WeightLayout layout(threeMeshes());
  std::vector<float> w = layout.defaults();
  EXPECT_EQ(*layout.setByName(w, "blink", 1.0f), 2);
  EXPECT_EQ(w, (std::vector<float>{0.1f, 1.0f, 1.0f, 0.5f, 0.0f}));
  EXPECT_EQ(*layout.setByName(w, "frown", 0.75f), 1);
  EXPECT_EQ(w[4], 0.75f);
  EXPECT_EQ(*layout.setByName(w, "nope", 1.0f), 0);
  EXPECT_EQ(layout.find(2, "jawOpen"), 3);
  EXPECT_EQ(layout.find(1, "smile"), -1);
  const auto mesh2 = *layout.meshWeights(w, 2);
  ASSERT_EQ(mesh2.size(), 3u);
  EXPECT_EQ(mesh2[1], 0.5f);
}

TEST(WeightLayout, ModelWithoutTargetsHasAnEmptyLayout) {
  eng::Model model;
  model.meshes.resize(2);
  const eng::WeightLayout layout(model);
  EXPECT_EQ(layout.total(), 0u);
  EXPECT_TRUE(layout.names().empty());
  std::vector<float> none;
  EXPECT_EQ(*layout.setByName(none, "x", 1.0f), 0);
}

TEST(WeightLayoutPreconditions, WrongSizedWeightsAreAnInvalidArgumentAndWriteNothing) {
  const eng::WeightLayout layout(threeMeshes());
  std::vector<float> w(4, 0.5f);
  const auto set = layout.setByName(w, "blink", 1.0f);
  ASSERT_FALSE(set.ok());
  EXPECT_EQ(set.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_EQ(set.error().message, "WeightLayout::setByName: weights has 4 entries, layout total is 5");
  EXPECT_EQ(w, std::vector<float>(4, 0.5f));

  const auto shortWeights = layout.meshWeights(w, 0);
  ASSERT_FALSE(shortWeights.ok());
  EXPECT_EQ(shortWeights.error().kind, eng::ErrorKind::InvalidArgument);
  const std::vector<float> full(5);
  const auto noMesh = layout.meshWeights(full, 3);
  ASSERT_FALSE(noMesh.ok());
  EXPECT_EQ(noMesh.error().message, "WeightLayout::meshWeights: mesh 3 outside 0..2");
}

TEST(WeightLayoutPreconditions, MeshIndicesOutsideTheLayoutHaveTheEmptyRangeAtTheEnd) {
  const eng::WeightLayout layout(threeMeshes());
  EXPECT_EQ(layout.offset(4), layout.total());
  EXPECT_EQ(layout.offset(-1), layout.total());
  EXPECT_EQ(layout.count(3), 0u);
  EXPECT_EQ(layout.count(-1), 0u);
}

}  // namespace
