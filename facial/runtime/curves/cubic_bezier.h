#pragma once
// CSS-style timing function: a cubic Bezier from (0,0) to (1,1) with
// editable handles (x1,y1) and (x2,y2). y is a function of x when both x
// handles lie in [0,1] (x(s) is then monotone), so evaluating means solving
// x(s) = x for s (Newton, with bisection when Newton stalls) and returning y(s).
#include "engine/core/result.h"

namespace facial {

struct CubicBezier {
  float x1 = 0.25f, y1 = 0.1f, x2 = 0.25f, y2 = 1.0f;  // CSS "ease"

  // Malformed when a handle is outside [0,1] in x or not finite.
  eng::Result<void> validate() const;

  // Curve parameter s in [0,1] whose x(s) equals x (x clamped to [0,1]).
  double solveParameter(double x) const;
  // y at x; x clamped to [0,1].
  float evaluate(float x) const;
  // dy/dx at x (infinite where the curve is vertical, e.g. x1 = 0 with y1 != 0 at x = 0).
  double slope(float x) const;
  // sup |dy/dx| over [0,1], sampled finely (the curve is smooth, so 2049
  // samples of the exact derivative bound it to well under a percent).
  double maxSlope() const;
};

}  // namespace facial
