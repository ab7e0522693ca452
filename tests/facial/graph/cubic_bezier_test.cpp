#include "facial/runtime/curves/cubic_bezier.h"

#include <cmath>

#include <gtest/gtest.h>

using facial::CubicBezier;

namespace {

// x(s), y(s) straight from the Bernstein form, to check the solver against.
float bernstein(float p1, float p2, float s) {
  const float u = 1 - s;
  return 3 * u * u * s * p1 + 3 * u * s * s * p2 + s * s * s;
}

}  // namespace

TEST(CubicBezier, DiagonalHandlesGiveTheIdentity) {
  const CubicBezier linear{0.0f, 0.0f, 1.0f, 1.0f};
  for (float x = 0.0f; x <= 1.0f; x += 0.05f) EXPECT_NEAR(linear.evaluate(x), x, 1e-6f);
}

TEST(CubicBezier, CssEaseMatchesTheBrowserValue) {
  // cubic-bezier(0.25, 0.1, 0.25, 1) at x = 0.5 is 0.80240338758 (bisection to 1e-15, offline).
  const CubicBezier ease{0.25f, 0.1f, 0.25f, 1.0f};
  EXPECT_NEAR(ease.evaluate(0.5f), 0.8024034f, 1e-5f);
  EXPECT_FLOAT_EQ(ease.evaluate(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(ease.evaluate(1.0f), 1.0f);
}

TEST(CubicBezier, SolverInvertsXForHardHandles) {
  // Flat spots in x(s) (x1 = x2 = 0 / 1) stall Newton; bisection must take over.
  for (const CubicBezier& c : {CubicBezier{0.0f, 0.0f, 0.0f, 1.0f}, CubicBezier{1.0f, 0.0f, 0.0f, 1.0f},
                               CubicBezier{1.0f, 0.2f, 1.0f, 0.8f}, CubicBezier{0.7f, -0.6f, 0.3f, 1.6f}}) {
    for (float x = 0.0f; x <= 1.0f; x += 1.0f / 64) {
      const double s = c.solveParameter(x);
      EXPECT_NEAR(bernstein(c.x1, c.x2, static_cast<float>(s)), x, 1e-5f) << c.x1 << "," << c.x2 << " x=" << x;
      EXPECT_NEAR(c.evaluate(x), bernstein(c.y1, c.y2, static_cast<float>(s)), 1e-5f);
    }
  }
}

TEST(CubicBezier, MaxSlopeBoundsTheFiniteDifferences) {
  const CubicBezier c{0.42f, 0.0f, 0.58f, 1.0f};  // CSS ease-in-out
  double worst = 0.0;
  const float h = 1e-3f;
  for (float x = 0.0f; x + h <= 1.0f; x += h) worst = std::max(worst, double(std::abs(c.evaluate(x + h) - c.evaluate(x))) / h);
  EXPECT_GE(c.maxSlope() * 1.001, worst);
  EXPECT_LE(c.maxSlope(), worst * 1.05);  // and is not loose
  EXPECT_TRUE(std::isinf((CubicBezier{0.0f, 1.0f, 1.0f, 1.0f}.maxSlope())));  // vertical start
}

TEST(CubicBezierValidity, HandleXMustLieInTheUnitInterval) {
  EXPECT_TRUE((CubicBezier{0.25f, 0.1f, 0.25f, 1.0f}.validate()));
  EXPECT_TRUE((CubicBezier{0.3f, -2.0f, 0.7f, 3.0f}.validate()));  // y may overshoot
  auto outside = CubicBezier{1.2f, 0.0f, 0.5f, 1.0f}.validate();
  ASSERT_FALSE(outside);
  EXPECT_EQ(outside.error().kind, eng::ErrorKind::Malformed);
  EXPECT_NE(outside.error().message.find("x1=1.2"), std::string::npos) << outside.error().message;
  EXPECT_FALSE((CubicBezier{0.2f, NAN, 0.5f, 1.0f}.validate()));
}
