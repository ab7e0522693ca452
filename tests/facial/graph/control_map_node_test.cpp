#include "facial/runtime/graph/nodes/control_map_node.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

TEST(ControlMapNode, WeightsFollowTheStudyPseudoCode) {
  // x >= 0: wE3 = x; x <= 0: wE4 = |x|; y >= 0: wE1 = y; y <= 0: wE2 = |y|; neutral = remainder.
  ControlMapWeights w = controlMapWeights(0.3f, -0.2f);
  EXPECT_FLOAT_EQ(w.e3, 0.3f);
  EXPECT_FLOAT_EQ(w.e4, 0.0f);
  EXPECT_FLOAT_EQ(w.e2, 0.2f);
  EXPECT_FLOAT_EQ(w.e1, 0.0f);
  EXPECT_FLOAT_EQ(w.neutral, 0.5f);

  w = controlMapWeights(-0.6f, 0.4f);
  EXPECT_FLOAT_EQ(w.e4, 0.6f);
  EXPECT_FLOAT_EQ(w.e1, 0.4f);
  EXPECT_NEAR(w.neutral, 0.0f, 1e-6f);

  w = controlMapWeights(0.0f, 0.0f);
  EXPECT_FLOAT_EQ(w.neutral, 1.0f);
  w = controlMapWeights(0.0f, 1.0f);
  EXPECT_FLOAT_EQ(w.e1, 1.0f);
  EXPECT_FLOAT_EQ(w.neutral, 0.0f);
}

TEST(ControlMapNode, CursorIsClampedToTheSquareThenThediamond) {
  ControlMapWeights w = controlMapWeights(3.0f, 0.0f);  // square clamp
  EXPECT_FLOAT_EQ(w.x, 1.0f);
  EXPECT_FLOAT_EQ(w.e3, 1.0f);
  w = controlMapWeights(0.8f, 0.6f);  // outside the diamond: scaled by 1 / 1.4
  EXPECT_NEAR(w.x, 0.8f / 1.4f, 1e-6f);
  EXPECT_NEAR(w.y, 0.6f / 1.4f, 1e-6f);
  EXPECT_NEAR(w.e3 + w.e1, 1.0f, 1e-6f);
  EXPECT_GE(w.neutral, 0.0f);
  w = controlMapWeights(-1.0f, -1.0f);  // corner: halfway between the two poles
  EXPECT_FLOAT_EQ(w.e4, 0.5f);
  EXPECT_FLOAT_EQ(w.e2, 0.5f);
  for (float x = -1.5f; x <= 1.5f; x += 0.1f)
    for (float y = -1.5f; y <= 1.5f; y += 0.1f) {
      w = controlMapWeights(x, y);
      EXPECT_NEAR(w.neutral + w.e1 + w.e2 + w.e3 + w.e4, 1.0f, 1e-5f);
      EXPECT_GE(w.neutral, 0.0f);
    }
}

TEST(ControlMapNode, OutputIsTheWeightedSumOfThePoles) {
  GraphBuilder b(threeChannels());
  const ParameterIndex x = b.addFloat("x"), y = b.addFloat("y");
  const NodeIndex neutral = addPose(b, {0.0f, 0.0f, 0.0f});
  const NodeIndex up = addPose(b, {1.0f, 0.0f, 0.0f});
  const NodeIndex down = addPose(b, {0.0f, 1.0f, 0.0f});
  const NodeIndex right = addPose(b, {0.0f, 0.0f, 1.0f});
  const NodeIndex left = addPose(b, {0.5f, 0.5f, 0.5f});
  b.setRoot(b.add(ControlMapNode{.neutral = neutral, .e1 = up, .e2 = down, .e3 = right, .e4 = left,
                                 .x = FloatInput::bound(x), .y = FloatInput::bound(y)}));
  GraphInstance face = instantiate(buildGraph(b));
  face.setFloat(x, -0.4f);
  face.setFloat(y, 0.3f);
  face.update(0.016f);
  EXPECT_NEAR(face.weights()[0], 0.3f + 0.4f * 0.5f, 1e-6f);
  EXPECT_NEAR(face.weights()[1], 0.4f * 0.5f, 1e-6f);
  EXPECT_NEAR(face.weights()[2], 0.4f * 0.5f, 1e-6f);
}

TEST(ControlMapNodeValidity, AxesMustBeParametersOfTheGraph) {
  GraphBuilder b(threeChannels());
  std::vector<NodeIndex> p;
  for (int i = 0; i < 5; ++i) p.push_back(addPose(b, {0, 0, 0}));
  b.setRoot(b.add(ControlMapNode{.neutral = p[0], .e1 = p[1], .e2 = p[2], .e3 = p[3], .e4 = p[4], .y = FloatInput::bound(3)}));
  EXPECT_NE(buildError(b).find("/y: parameter index 3 out of range"), std::string::npos);
}
