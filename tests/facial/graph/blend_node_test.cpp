#include "facial/runtime/graph/nodes/blend_node.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

// P0 = (0, 1, 0.2), P1 = (1, 0, 0.6) blended by parameter "t" with `curve`.
struct BlendRig {
  explicit BlendRig(EasingCurve curve) {
    GraphBuilder b(threeChannels());
    t = b.addFloat("t");
    const NodeIndex p0 = addPose(b, {0.0f, 1.0f, 0.2f});
    const NodeIndex p1 = addPose(b, {1.0f, 0.0f, 0.6f});
    b.setRoot(b.add(BlendNode{.a = p0, .b = p1, .factor = FloatInput::bound(t), .curve = std::move(curve)}));
    face.emplace(instantiate(buildGraph(b)));
  }
  std::vector<float> at(float value) {
    face->setFloat(t, value);
    face->update(0.016f);
    return {face->weights().begin(), face->weights().end()};
  }
  ParameterIndex t = 0;
  std::optional<GraphInstance> face;
};

// The cubic Bezier through (0, 0), (x1, y1), (x2, y2), (1, 1) at `x`, worked
// out here independently of CubicBezier's solver: x(s) rises monotonically
// in s for x1, x2 in [0, 1], so bisection finds s with x(s) = x; the answer
// is y(s).
double bezierAt(double x1, double y1, double x2, double y2, double x) {
  auto coordinate = [](double s, double p1, double p2) {
    return 3 * (1 - s) * (1 - s) * s * p1 + 3 * (1 - s) * s * s * p2 + s * s * s;
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i) {
    const double mid = (lo + hi) / 2;
    (coordinate(mid, x1, x2) < x ? lo : hi) = mid;
  }
  return coordinate((lo + hi) / 2, y1, y2);
}

void expectBlend(const std::vector<float>& w, float c) {
  EXPECT_NEAR(w[0], c, 1e-6f);
  EXPECT_NEAR(w[1], 1.0f - c, 1e-6f);
  EXPECT_NEAR(w[2], (1.0f - c) * 0.2f + c * 0.6f, 1e-6f);
}

}  // namespace

TEST(BlendNode, LinearIsOneMinusTP0PlusTP1) {
  BlendRig rig(EasingCurve::linear());
  expectBlend(rig.at(0.0f), 0.0f);
  expectBlend(rig.at(0.3f), 0.3f);
  expectBlend(rig.at(1.0f), 1.0f);
  expectBlend(rig.at(1.7f), 1.0f);  // factor clamped
}

TEST(BlendNode, CosineUsesOneMinusCosPiTOverTwo) {
  BlendRig rig(EasingCurve::cosine());
  for (float t : {0.1f, 0.25f, 0.5f, 0.8f})
    expectBlend(rig.at(t), (1.0f - std::cos(std::numbers::pi_v<float> * t)) / 2.0f);
}

TEST(BlendNode, SmoothstepUsesThreeTSquaredMinusTwoTCubed) {
  BlendRig rig(EasingCurve::smoothstep());
  for (float t : {0.1f, 0.25f, 0.5f, 0.8f}) expectBlend(rig.at(t), 3 * t * t - 2 * t * t * t);
}

TEST(BlendNode, BezierHandlesShapeTheBlend) {
  auto curve = EasingCurve::bezier({0.25f, 0.1f, 0.25f, 1.0f});
  ASSERT_TRUE(curve.ok());
  BlendRig rig(*curve);
  // CSS's `ease` curve: at x = 0.5 it is about 0.8024, far above the linear 0.5.
  for (float x : {0.1f, 0.5f, 0.9f}) expectBlend(rig.at(x), static_cast<float>(bezierAt(0.25, 0.1, 0.25, 1.0, x)));
  EXPECT_NEAR(rig.at(0.5f)[0], 0.8024f, 1e-4f);
}

TEST(BlendNode, KeyedCurveShapesTheBlend) {
  auto curve = EasingCurve::keyed({Keyframe{0, 0}, Keyframe{0.5f, 0.2f}, Keyframe{1, 1}});
  ASSERT_TRUE(curve.ok());
  BlendRig rig(*curve);
  expectBlend(rig.at(0.25f), 0.1f);
  expectBlend(rig.at(0.75f), 0.6f);
}

TEST(BlendNodeValidity, FactorMustNameAnExistingParameter) {
  GraphBuilder b(threeChannels());
  const NodeIndex p0 = addPose(b, {0, 0, 0});
  const NodeIndex p1 = addPose(b, {1, 1, 1});
  b.setRoot(b.add(BlendNode{.a = p0, .b = p1, .factor = FloatInput::bound(7)}));
  EXPECT_NE(buildError(b).find("node 2 (blend)/factor: parameter index 7 out of range (0 parameters)"), std::string::npos);
}
