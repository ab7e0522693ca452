#include "facial/runtime/curves/easing_curve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

std::string_view easingTypeName(EasingType value) { return eng::nameOf(kEasingTypeNames, value); }

std::optional<EasingType> easingTypeFromName(std::string_view name) { return eng::valueNamed(kEasingTypeNames, name); }

EasingCurve::EasingCurve(EasingType type) : type_(type) {
  switch (type) {
    case EasingType::Linear: maxSlope_ = 1.0; break;
    case EasingType::Cosine: maxSlope_ = std::numbers::pi / 2.0; break;  // at t = 1/2
    case EasingType::Smoothstep: maxSlope_ = 1.5; break;                 // 6t - 6t^2 at t = 1/2
    default: break;
  }
}

eng::Result<EasingCurve> EasingCurve::bezier(const CubicBezier& handles) {
  if (auto valid = handles.validate(); !valid) return valid.error();
  EasingCurve curve(EasingType::CubicBezier);
  curve.bezier_ = handles;
  curve.maxSlope_ = handles.maxSlope();
  return curve;
}

eng::Result<EasingCurve> EasingCurve::keyed(std::vector<Keyframe> keys) {
  if (auto valid = validateKeys(keys); !valid) return valid.error().prefixed("keyed curve: ");
  if (keys.size() < 2 || keys.front().time != 0.0f || keys.front().value != 0.0f || keys.back().time != 1.0f ||
      keys.back().value != 1.0f)
    return eng::makeError(eng::ErrorKind::Malformed, "keyed curve must start at (0,0) and end at (1,1) (got " + std::to_string(keys.size()) +
                          " keys from (" + formatNumber(keys.front().time) + "," +
                          formatNumber(keys.front().value) + ") to (" + formatNumber(keys.back().time) + "," +
                          formatNumber(keys.back().value) + "))");
  EasingCurve curve(EasingType::Keyed);
  double slope = 0.0;
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    const Keyframe& k0 = keys[i];
    const Keyframe& k1 = keys[i + 1];
    if (k0.interpolation == KeyInterpolation::Step) {
      if (k0.value != k1.value) slope = std::numeric_limits<double>::infinity();
      continue;
    }
    // The derivative is constant (linear), a sine bump peaking mid-segment
    // (cosine) or a quadratic (Hermite): its extremes lie at the ends, the
    // middle, or the quadratic's vertex.
    const float length = k1.time - k0.time;
    std::vector<float> probes = {k0.time, k1.time, k0.time + 0.5f * length};
    if (k0.interpolation == KeyInterpolation::Hermite) {
      const double d0 = segmentDerivative(k0, k1, k0.time);
      const double dm = segmentDerivative(k0, k1, k0.time + 0.5f * length);
      const double d1 = segmentDerivative(k0, k1, k1.time);
      const double a = 2.0 * (d0 + d1 - 2.0 * dm);  // d(s) = a s^2 + b s + c through the three probes
      const double b = d1 - d0 - a;
      if (std::abs(a) > 1e-12) {
        const double vertex = -b / (2.0 * a);
        if (vertex > 0.0 && vertex < 1.0) probes.push_back(k0.time + static_cast<float>(vertex) * length);
      }
    }
    for (float t : probes) slope = std::max(slope, std::abs(static_cast<double>(segmentDerivative(k0, k1, t))));
  }
  curve.maxSlope_ = slope;
  curve.keys_ = std::move(keys);
  return curve;
}

float EasingCurve::operator()(float t) const {
  t = std::clamp(t, 0.0f, 1.0f);
  switch (type_) {
    case EasingType::Linear: return t;
    case EasingType::Cosine: return 0.5f * (1.0f - std::cos(std::numbers::pi_v<float> * t));
    case EasingType::Smoothstep: return t * t * (3.0f - 2.0f * t);
    case EasingType::CubicBezier: return bezier_.evaluate(t);
    case EasingType::Keyed: return sampleKeys(keys_, t);
  }
  return t;
}

}  // namespace facial
