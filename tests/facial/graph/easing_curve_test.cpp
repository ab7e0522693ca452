#include "facial/runtime/curves/easing_curve.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

using facial::EasingCurve;
using facial::Keyframe;
using facial::KeyInterpolation;

namespace {

// Largest |c(t+h) - c(t)| / h over [0,1].
double finiteDifferenceSlope(const EasingCurve& c) {
  double worst = 0.0;
  const float h = 1.0f / 4096;
  for (int i = 0; i < 4096; ++i) worst = std::max(worst, double(std::abs(c((i + 1) * h) - c(i * h))) / h);
  return worst;
}

}  // namespace

TEST(EasingCurve, FixedShapesFollowTheirFormulas) {
  for (float t : {0.0f, 0.1f, 0.3f, 0.5f, 0.77f, 1.0f}) {
    EXPECT_FLOAT_EQ(EasingCurve::linear()(t), t);
    EXPECT_NEAR(EasingCurve::cosine()(t), (1.0f - std::cos(std::numbers::pi_v<float> * t)) / 2.0f, 1e-6f);
    EXPECT_NEAR(EasingCurve::smoothstep()(t), 3 * t * t - 2 * t * t * t, 1e-6f);
  }
  EXPECT_FLOAT_EQ(EasingCurve::cosine()(-1.0f), 0.0f);  // clamped
  EXPECT_FLOAT_EQ(EasingCurve::cosine()(2.0f), 1.0f);
}

TEST(EasingCurve, MaxSlopeIsTheTrueSupremum) {
  auto bezier = EasingCurve::bezier({0.42f, 0.0f, 0.58f, 1.0f});
  auto keyed = EasingCurve::keyed({Keyframe{0, 0, 0, 0, KeyInterpolation::Cosine}, Keyframe{0.25f, 0.5f},
                                   Keyframe{0.5f, 0.6f, 0, 0.5f, KeyInterpolation::Hermite}, Keyframe{1, 1, 3.0f, 0}});
  ASSERT_TRUE(bezier.ok());
  ASSERT_TRUE(keyed.ok()) << keyed.error().message;
  EXPECT_DOUBLE_EQ(EasingCurve::cosine().maxSlope(), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(EasingCurve::smoothstep().maxSlope(), 1.5);
  const EasingCurve linear = EasingCurve::linear();
  for (const EasingCurve* c : std::initializer_list<const EasingCurve*>{&linear, &bezier.value(), &keyed.value()}) {
    const double measured = finiteDifferenceSlope(*c);
    EXPECT_GE(c->maxSlope() * 1.001, measured) << facial::easingTypeName(c->type());
    EXPECT_LE(c->maxSlope(), measured * 1.02) << facial::easingTypeName(c->type());
  }
}

TEST(EasingCurve, KeyedCurveInterpolatesItsKeys) {
  auto c = EasingCurve::keyed({Keyframe{0, 0}, Keyframe{0.5f, 0.8f}, Keyframe{1, 1}});
  ASSERT_TRUE(c.ok());
  EXPECT_FLOAT_EQ((*c)(0.25f), 0.4f);
  EXPECT_FLOAT_EQ((*c)(0.75f), 0.9f);
  EXPECT_NEAR(c->maxSlope(), 1.6, 1e-6);
}

TEST(EasingCurveValidity, KeyedCurveMustRunFromOriginToOne) {
  auto late = EasingCurve::keyed({Keyframe{0.1f, 0}, Keyframe{1, 1}});
  ASSERT_FALSE(late.ok());
  EXPECT_NE(late.error().message.find("(0,0)"), std::string::npos) << late.error().message;
  EXPECT_FALSE(EasingCurve::keyed({Keyframe{0, 0}, Keyframe{1, 0.9f}}).ok());
  EXPECT_FALSE(EasingCurve::keyed({Keyframe{0, 0}, Keyframe{0, 1}}).ok());  // unsorted
  EXPECT_TRUE(std::isinf(EasingCurve::keyed({Keyframe{0, 0, 0, 0, KeyInterpolation::Step}, Keyframe{1, 1}})->maxSlope()));
}

TEST(EasingCurveValidity, BezierRejectsHandlesOutsideTheUnitInterval) {
  auto c = EasingCurve::bezier({-0.1f, 0.0f, 0.5f, 1.0f});
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("x1=-0.1"), std::string::npos) << c.error().message;
}
