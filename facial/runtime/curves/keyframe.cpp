#include "facial/runtime/curves/keyframe.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

std::string_view keyInterpolationName(KeyInterpolation value) { return eng::nameOf(kKeyInterpolationNames, value); }

std::optional<KeyInterpolation> keyInterpolationFromName(std::string_view name) { return eng::valueNamed(kKeyInterpolationNames, name); }

std::string_view tangentModeName(TangentMode value) { return eng::nameOf(kTangentModeNames, value); }

std::optional<TangentMode> tangentModeFromName(std::string_view name) { return eng::valueNamed(kTangentModeNames, name); }

namespace {

// Catmull-Rom slope through the neighbours; 0 at the ends, at a peak or a dip
// and beside a level neighbour (the curve would overshoot the key otherwise).
float autoSlope(std::span<const Keyframe> keys, size_t i) {
  if (i == 0 || i + 1 >= keys.size()) return 0.0f;
  const Keyframe &a = keys[i - 1], &k = keys[i], &b = keys[i + 1];
  if ((k.value - a.value) * (b.value - k.value) <= 0.0f) return 0.0f;
  return (b.value - a.value) / (b.time - a.time);
}

}  // namespace

void resolveTangents(std::span<Keyframe> keys) {
  for (size_t i = 0; i < keys.size(); ++i) {
    Keyframe& k = keys[i];
    switch (k.tangent) {
      case TangentMode::Broken: break;
      case TangentMode::Auto: k.inTangent = k.outTangent = autoSlope(keys, i); break;
      case TangentMode::Smooth: k.inTangent = k.outTangent; break;
      case TangentMode::Flat: k.inTangent = k.outTangent = 0.0f; break;
    }
  }
}

eng::Result<void> validateKeys(std::span<const Keyframe> keys) {
  if (keys.empty()) return eng::makeError(eng::ErrorKind::Malformed, "no keys");
  for (size_t i = 0; i < keys.size(); ++i) {
    const Keyframe& k = keys[i];
    const std::pair<const char*, float> numbers[] = {
        {"time", k.time}, {"value", k.value}, {"in-tangent", k.inTangent}, {"out-tangent", k.outTangent}};
    for (const auto& [field, v] : numbers)
      if (!(std::abs(v) <= kMaxKeyMagnitude))
        return eng::makeError(eng::ErrorKind::Malformed, "key " + std::to_string(i) + " " + field + " " + formatNumber(v) +
                                                             " is not a finite number within [-1e+06, 1e+06]");
    if (i > 0 && !(k.time > keys[i - 1].time))
      return eng::makeError(eng::ErrorKind::Malformed, "key " + std::to_string(i) + " time " + formatNumber(k.time) +
                                                           " is not after key " + std::to_string(i - 1) + " time " +
                                                           formatNumber(keys[i - 1].time) +
                                                           " (keys must be sorted, no duplicates)");
  }
  return {};
}

namespace {

// Hermite basis on s in [0,1] with tangents scaled by the segment length.
float hermite(float v0, float m0, float v1, float m1, float length, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * length * m0 + (-2 * s3 + 3 * s2) * v1 +
         (s3 - s2) * length * m1;
}

float hermiteDerivative(float v0, float m0, float v1, float m1, float length, float s) {
  const float s2 = s * s;
  // d/ds of the basis, divided by length for d/dtime.
  return ((6 * s2 - 6 * s) * v0 + (3 * s2 - 4 * s + 1) * length * m0 + (-6 * s2 + 6 * s) * v1 +
          (3 * s2 - 2 * s) * length * m1) /
         length;
}

}  // namespace

float interpolateSegment(const Keyframe& k0, const Keyframe& k1, float time) {
  const float length = k1.time - k0.time;
  const float s = std::clamp((time - k0.time) / length, 0.0f, 1.0f);
  switch (k0.interpolation) {
    case KeyInterpolation::Step: return s < 1.0f ? k0.value : k1.value;
    case KeyInterpolation::Linear: return k0.value + (k1.value - k0.value) * s;
    case KeyInterpolation::Cosine:
      return k0.value + (k1.value - k0.value) * 0.5f * (1.0f - std::cos(std::numbers::pi_v<float> * s));
    case KeyInterpolation::Hermite: return hermite(k0.value, k0.outTangent, k1.value, k1.inTangent, length, s);
  }
  return k0.value;
}

float segmentDerivative(const Keyframe& k0, const Keyframe& k1, float time) {
  const float length = k1.time - k0.time;
  const float s = std::clamp((time - k0.time) / length, 0.0f, 1.0f);
  switch (k0.interpolation) {
    case KeyInterpolation::Step: return 0.0f;
    case KeyInterpolation::Linear: return (k1.value - k0.value) / length;
    case KeyInterpolation::Cosine:
      return (k1.value - k0.value) * 0.5f * std::numbers::pi_v<float> * std::sin(std::numbers::pi_v<float> * s) /
             length;
    case KeyInterpolation::Hermite:
      return hermiteDerivative(k0.value, k0.outTangent, k1.value, k1.inTangent, length, s);
  }
  return 0.0f;
}

uint32_t findSegment(std::span<const Keyframe> keys, float time) {
  if (keys.size() < 2) return 0;
  // First key strictly after `time`; the segment starts one before it.
  auto it = std::upper_bound(keys.begin() + 1, keys.end() - 1, time,
                             [](float t, const Keyframe& k) { return t < k.time; });
  return static_cast<uint32_t>(it - keys.begin()) - 1;
}

uint32_t findSegment(std::span<const Keyframe> keys, float time, uint32_t cursor) {
  if (keys.size() < 2) return 0;
  const uint32_t last = static_cast<uint32_t>(keys.size()) - 2;
  if (cursor > last || time < keys[cursor].time) return findSegment(keys, time);
  // Forward playback moves at most a key or two per frame: walk a few, then search.
  for (int step = 0; step < 4; ++step) {
    if (cursor == last || time < keys[cursor + 1].time) return cursor;
    ++cursor;
  }
  return findSegment(keys, time);
}

float sampleKeys(std::span<const Keyframe> keys, float time) {
  uint32_t cursor = findSegment(keys, time);
  return sampleKeys(keys, time, cursor);
}

float sampleKeys(std::span<const Keyframe> keys, float time, uint32_t& cursor) {
  if (keys.size() == 1 || time <= keys.front().time) {
    cursor = 0;
    return keys.front().value;
  }
  if (time >= keys.back().time) {
    cursor = static_cast<uint32_t>(keys.size()) - 2;
    return keys.back().value;
  }
  cursor = findSegment(keys, time, cursor);
  return interpolateSegment(keys[cursor], keys[cursor + 1], time);
}

}  // namespace facial
