#include "facial/runtime/graph/nodes/freeform_map_node.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

// Six emotions around the valence/arousal circle (Russell's circumplex order), neutral at the centre.
std::vector<glm::vec2> circumplex() {
  std::vector<glm::vec2> points = {glm::vec2(0.0f)};
  for (float degrees : {30.0f, 90.0f, 150.0f, 200.0f, 250.0f, 320.0f}) {
    const float a = degrees * std::numbers::pi_v<float> / 180.0f;
    points.emplace_back(std::cos(a), std::sin(a));
  }
  return points;
}

std::vector<float> weightsAt(const std::vector<glm::vec2>& points, glm::vec2 p) {
  std::vector<float> w(points.size());
  gradientBandWeights(points, p, w);
  return w;
}

}  // namespace

TEST(FreeformMapNode, EachPoleIsReproducedExactly) {
  const auto points = circumplex();
  for (size_t i = 0; i < points.size(); ++i) {
    const std::vector<float> w = weightsAt(points, points[i]);
    for (size_t j = 0; j < w.size(); ++j) EXPECT_FLOAT_EQ(w[j], i == j ? 1.0f : 0.0f) << "pole " << i << " weight " << j;
  }
}

TEST(FreeformMapNode, WeightsAreAPartitionOfUnityAndOnlyNeighboursMix) {
  const auto points = circumplex();
  for (float x = -1.0f; x <= 1.0f; x += 0.05f)
    for (float y = -1.0f; y <= 1.0f; y += 0.05f) {
      if (x * x + y * y > 1.0f) continue;
      const std::vector<float> w = weightsAt(points, {x, y});
      float sum = 0.0f;
      for (float v : w) {
        EXPECT_GE(v, 0.0f);
        sum += v;
      }
      EXPECT_NEAR(sum, 1.0f, 1e-5f);
    }
  // Halfway between two adjacent poles on the rim the opposite pole has no say.
  const std::vector<float> w = weightsAt(points, (points[1] + points[2]) * 0.5f);
  EXPECT_FLOAT_EQ(w[4], 0.0f);
  EXPECT_GT(w[1], 0.3f);
  EXPECT_GT(w[2], 0.3f);
}

TEST(FreeformMapNode, WeightsAreContinuousWithABoundedGradient) {
  // Each band h_i is a clamped affine function with gradient at most
  // 1 / (closest pole distance); the normalisation keeps the weights
  // Lipschitz. Fine steps anywhere in the disc never jump.
  const auto points = circumplex();
  const float h = 1e-3f;
  float steepest = 0.0f;
  for (float x = -1.0f; x <= 1.0f; x += 0.013f)
    for (float y = -1.0f; y <= 1.0f; y += 0.017f) {
      if (x * x + y * y > 0.98f) continue;
      const std::vector<float> w0 = weightsAt(points, {x, y});
      for (glm::vec2 d : {glm::vec2(h, 0.0f), glm::vec2(0.0f, h)}) {
        const std::vector<float> w1 = weightsAt(points, glm::vec2(x, y) + d);
        for (size_t i = 0; i < w0.size(); ++i) steepest = std::max(steepest, std::abs(w1[i] - w0[i]) / h);
      }
    }
  EXPECT_LT(steepest, 10.0f);  // closest pair ~0.77 apart: bands change by ~1.3 per unit; normalising adds a few
  EXPECT_GT(steepest, 0.5f);   // and the weights do move
}

TEST(FreeformMapNode, NodeClampsTheCursorToTheDiscThroughTheFarthestPole) {
  GraphBuilder b(threeChannels());
  const ParameterIndex x = b.addFloat("valence"), y = b.addFloat("arousal");
  FreeformMapNode node{.neutral = addPose(b, {0.0f, 0.0f, 0.0f})};
  node.poles = {{{1.0f, 0.0f}, addPose(b, {1.0f, 0.0f, 0.0f})},
                {{0.0f, 1.0f}, addPose(b, {0.0f, 1.0f, 0.0f})},
                {{-1.0f, -1.0f}, addPose(b, {0.0f, 0.0f, 1.0f})}};
  node.x = FloatInput::bound(x);
  node.y = FloatInput::bound(y);
  b.setRoot(b.add(node));
  GraphInstance face = instantiate(buildGraph(b));
  face.setFloat(x, 1.0f);
  face.update(0.0f);
  EXPECT_NEAR(face.weights()[0], 1.0f, 1e-6f);  // exactly on a pole
  face.setFloat(x, -30.0f);
  face.setFloat(y, -30.0f);
  face.update(0.0f);
  EXPECT_NEAR(face.weights()[2], 1.0f, 1e-5f);  // far out along the diagonal: clamped onto pole (-1,-1)
  face.setFloat(x, 0.0f);
  face.setFloat(y, 0.0f);
  face.update(0.0f);
  EXPECT_FLOAT_EQ(face.weights()[0] + face.weights()[1] + face.weights()[2], 0.0f);  // neutral at the centre
}

TEST(FreeformMapNodeValidity, PolesMustBeDistinctAndOffCentre) {
  GraphBuilder b(threeChannels());
  FreeformMapNode node{.neutral = addPose(b, {0, 0, 0})};
  node.poles = {{{0.5f, 0.5f}, addPose(b, {1, 0, 0})}, {{0.5f, 0.5f}, addPose(b, {0, 1, 0})}};
  b.setRoot(b.add(node));
  EXPECT_NE(buildError(b).find("/poles/1/at: pole lies on pole 0"), std::string::npos);

  GraphBuilder c(threeChannels());
  FreeformMapNode centre{.neutral = addPose(c, {0, 0, 0})};
  centre.poles = {{{0.0f, 0.0f}, addPose(c, {1, 0, 0})}};
  c.setRoot(c.add(centre));
  EXPECT_NE(buildError(c).find("/poles/0/at: pole lies on neutral"), std::string::npos);

  GraphBuilder d(threeChannels());
  d.setRoot(d.add(FreeformMapNode{.neutral = addPose(d, {0, 0, 0})}));
  EXPECT_NE(buildError(d).find("/poles: needs 1 to 32 poles, got 0"), std::string::npos);
}
