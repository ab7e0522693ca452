#pragma once
// Easing curve c: [0,1] -> R with c(0) = 0 and c(1) = 1, used by blends and
// transitions as P = (1 - c(t)) P0 + c(t) P1. Immutable value type; a keyed
// curve owns its keys (allocated when built, never while evaluating).
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/core/result.h"
#include "facial/runtime/curves/cubic_bezier.h"
#include "facial/runtime/curves/keyframe.h"

namespace facial {

enum class EasingType : uint8_t {
  Linear,       // c(t) = t
  Cosine,       // c(t) = (1 - cos(pi t)) / 2
  Smoothstep,   // c(t) = 3t^2 - 2t^3
  CubicBezier,  // CSS cubic-bezier(x1, y1, x2, y2)
  Keyed,        // keys over [0,1], each with its own interpolation
};

inline constexpr eng::EnumName<EasingType> kEasingTypeNames[] = {
    {EasingType::Linear, "linear"},
    {EasingType::Cosine, "cosine"},
    {EasingType::Smoothstep, "smoothstep"},
    {EasingType::CubicBezier, "bezier"},
    {EasingType::Keyed, "keyed"},
};
std::string_view easingTypeName(EasingType value);
std::optional<EasingType> easingTypeFromName(std::string_view name);

class EasingCurve {
 public:
  EasingCurve() = default;  // linear
  static EasingCurve linear() { return EasingCurve(EasingType::Linear); }
  static EasingCurve cosine() { return EasingCurve(EasingType::Cosine); }
  static EasingCurve smoothstep() { return EasingCurve(EasingType::Smoothstep); }
  // Fails when a handle's x lies outside [0,1] or is not finite.
  static eng::Result<EasingCurve> bezier(const CubicBezier& handles);
  // Fails unless the keys are valid (sorted, finite), start at (0,0) and end at (1,1):
  // a curve that does not would make every transition jump at its ends.
  static eng::Result<EasingCurve> keyed(std::vector<Keyframe> keys);

  EasingType type() const { return type_; }
  const CubicBezier& handles() const { return bezier_; }
  std::span<const Keyframe> keys() const { return keys_; }

  // c(t), t clamped to [0,1].
  float operator()(float t) const;
  // sup |c'(t)| over [0,1]: exact for the fixed shapes and keyed curves
  // (per segment), sampled for Bezier; infinite for a jump (Step key) or a
  // vertical Bezier end. Transition code divides it by the duration to
  // bound how fast a weight can move.
  double maxSlope() const { return maxSlope_; }

 private:
  explicit EasingCurve(EasingType type);

  EasingType type_ = EasingType::Linear;
  CubicBezier bezier_{};
  std::vector<Keyframe> keys_;
  double maxSlope_ = 1.0;
};

}  // namespace facial
