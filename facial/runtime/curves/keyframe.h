#pragma once
// One key of a scalar curve and the interpolation of the segment it starts.
// Keys live in sorted flat arrays (a timeline track, a keyed easing curve);
// sampling walks them with a cursor so forward playback costs O(1) amortised.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/enum_names.h"
#include "engine/core/result.h"

namespace facial {

// How the segment [key k, key k+1] is filled; key k's mode decides.
enum class KeyInterpolation : uint8_t {
  Step,     // hold key k's value until key k+1
  Linear,   // straight line
  Cosine,   // (1 - cos(pi s)) / 2 ease between the two values
  Hermite,  // cubic Hermite: key k's outTangent, key k+1's inTangent (value per second)
};

// Where a key's tangents (inTangent, outTangent) come from. The curve editor
// and the runtime both resolve them with resolveTangents(), so a clip plays
// exactly the curve the editor draws.
enum class TangentMode : uint8_t {
  Broken,  // in and out as given, independent (the default: files without modes keep their slopes)
  Auto,    // Catmull-Rom through the neighbours, flat at the ends and at a peak or dip (no overshoot there)
  Smooth,  // one slope both sides: out is given, in follows it
  Flat,    // both 0
};

struct Keyframe {
  float time = 0;
  float value = 0;
  float inTangent = 0;   // d value / d time arriving at this key (Hermite segments ending here)
  float outTangent = 0;  // d value / d time leaving this key (Hermite segment starting here)
  KeyInterpolation interpolation = KeyInterpolation::Linear;
  TangentMode tangent = TangentMode::Broken;
};

inline constexpr eng::EnumName<KeyInterpolation> kKeyInterpolationNames[] = {
    {KeyInterpolation::Step, "step"},
    {KeyInterpolation::Linear, "linear"},
    {KeyInterpolation::Cosine, "cosine"},
    {KeyInterpolation::Hermite, "hermite"},
};
std::string_view keyInterpolationName(KeyInterpolation value);
std::optional<KeyInterpolation> keyInterpolationFromName(std::string_view name);

inline constexpr eng::EnumName<TangentMode> kTangentModeNames[] = {
    {TangentMode::Broken, "broken"},
    {TangentMode::Auto, "auto"},
    {TangentMode::Smooth, "smooth"},
    {TangentMode::Flat, "flat"},
};
std::string_view tangentModeName(TangentMode value);
std::optional<TangentMode> tangentModeFromName(std::string_view name);

// Sets each key's inTangent / outTangent from its TangentMode (sorted keys;
// Broken keys are left alone). Run after every edit of a key array and after
// reading one, so editor and runtime sample the same curve.
void resolveTangents(std::span<Keyframe> keys);

// Times, values and tangents (weight per second) of a key stay within this:
// real curves hold seconds and weights of a few units, while a tangent of
// 1e30 times a segment's length overflows to infinity.
inline constexpr float kMaxKeyMagnitude = 1e6f;

// Malformed when a key array is unusable (unsorted or duplicate times, a
// number not finite or past kMaxKeyMagnitude, empty). Messages name the key
// index and the field.
eng::Result<void> validateKeys(std::span<const Keyframe> keys);

// Value of the segment that starts at k0 and ends at k1, at `time` in [k0.time, k1.time].
float interpolateSegment(const Keyframe& k0, const Keyframe& k1, float time);
// d value / d time of that segment at `time` (0 for Step).
float segmentDerivative(const Keyframe& k0, const Keyframe& k1, float time);

// Index of the segment holding `time`: the last key with key.time <= time,
// clamped to [0, keys.size() - 2] (0 for a single key). Binary search.
uint32_t findSegment(std::span<const Keyframe> keys, float time);
// Same answer, starting from `cursor` (the previous answer): a few steps
// forward for playback, a binary search for seeks and backward jumps.
uint32_t findSegment(std::span<const Keyframe> keys, float time, uint32_t cursor);

// The curve's value at `time`; before the first key / after the last the
// end values hold. keys must pass validateKeys.
float sampleKeys(std::span<const Keyframe> keys, float time);
float sampleKeys(std::span<const Keyframe> keys, float time, uint32_t& cursor);

}  // namespace facial
