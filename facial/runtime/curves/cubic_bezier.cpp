#include "facial/runtime/curves/cubic_bezier.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {
namespace {

// Bernstein form with P0 = 0, P3 = 1: B(s) = 3(1-s)^2 s p1 + 3(1-s) s^2 p2 + s^3.
double bezier(double p1, double p2, double s) {
  const double u = 1.0 - s;
  return 3.0 * u * u * s * p1 + 3.0 * u * s * s * p2 + s * s * s;
}

double bezierDerivative(double p1, double p2, double s) {
  const double u = 1.0 - s;
  return 3.0 * u * u * p1 + 6.0 * u * s * (p2 - p1) + 3.0 * s * s * (1.0 - p2);
}

}  // namespace

eng::Result<void> CubicBezier::validate() const {
  for (float v : {x1, y1, x2, y2})
    if (!std::isfinite(v)) return eng::makeError(eng::ErrorKind::Malformed, "bezier handle is not a finite number");
  if (x1 < 0 || x1 > 1 || x2 < 0 || x2 > 1)
    return eng::makeError(eng::ErrorKind::Malformed, "bezier handle x must lie in [0,1] (got x1=" + formatNumber(x1) +
                                                         ", x2=" + formatNumber(x2) + ")");
  return {};
}

double CubicBezier::solveParameter(double x) const {
  x = std::clamp(x, 0.0, 1.0);
  // Newton from s = x converges in a handful of steps for usual handles.
  double s = x;
  for (int i = 0; i < 8; ++i) {
    const double error = bezier(x1, x2, s) - x;
    if (std::abs(error) < 1e-9) return s;
    const double d = bezierDerivative(x1, x2, s);
    if (std::abs(d) < 1e-6) break;  // flat spot: Newton would shoot off
    s -= error / d;
    if (s < 0.0 || s > 1.0) break;
  }
  // Bisection always converges because x(s) is monotone for x handles in [0,1].
  double lo = 0.0, hi = 1.0;
  s = x;
  for (int i = 0; i < 60; ++i) {
    const double value = bezier(x1, x2, s);
    if (std::abs(value - x) < 1e-10) break;
    (value < x ? lo : hi) = s;
    s = 0.5 * (lo + hi);
  }
  return s;
}

float CubicBezier::evaluate(float x) const {
  if (x <= 0.0f) return 0.0f;
  if (x >= 1.0f) return 1.0f;
  return static_cast<float>(bezier(y1, y2, solveParameter(x)));
}

double CubicBezier::slope(float x) const {
  const double s = solveParameter(x);
  const double dx = bezierDerivative(x1, x2, s);
  const double dy = bezierDerivative(y1, y2, s);
  if (dx <= 0.0) return dy == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return dy / dx;
}

double CubicBezier::maxSlope() const {
  double best = 0.0;
  constexpr int kSamples = 2048;
  for (int i = 0; i <= kSamples; ++i) {
    const double s = static_cast<double>(i) / kSamples;
    const double dx = bezierDerivative(x1, x2, s);
    const double dy = std::abs(bezierDerivative(y1, y2, s));
    if (dx <= 1e-12) {
      if (dy > 0.0) return std::numeric_limits<double>::infinity();
      continue;
    }
    best = std::max(best, dy / dx);
  }
  return best;
}

}  // namespace facial
