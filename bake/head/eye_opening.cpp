#include "bake/head/eye_opening.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bake {
namespace {

constexpr int kArcSamples = 720;

float radians(float degrees) { return degrees * std::numbers::pi_v<float> / 180.0f; }
float degrees(float radians) { return radians * 180.0f / std::numbers::pi_v<float>; }

}  // namespace

EyeOpening::EyeOpening(const HeadProportions& p, float side)
    : side_(side),
      centre_(p.eyeCentre.x * side, p.eyeCentre.y, p.eyeCentre.z),
      radius_(p.eyeRadius),
      inner_(p.innerCornerA, p.innerCornerB),
      outer_(p.outerCornerA, p.outerCornerB),
      upperHeight_(p.upperLidHeight),
      lowerDepth_(p.lowerLidDepth) {
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (int i = 0; i <= kArcSamples; ++i) {
    const float t = float(i) / kArcSamples;
    lo = glm::min(lo, glm::min(upperLid(t), lowerLid(t)));
    hi = glm::max(hi, glm::max(upperLid(t), lowerLid(t)));
  }
  middle_ = 0.5f * (lo + hi);
  halfExtent_ = 0.5f * (hi - lo);
  for (int i = 0; i < kArcSamples; ++i) {
    loop_.push_back(upperLid(float(i) / kArcSamples));
    loopUpper_.push_back(true);
  }
  for (int i = 0; i < kArcSamples; ++i) {
    loop_.push_back(lowerLid(1.0f - float(i) / kArcSamples));
    loopUpper_.push_back(false);
  }
  for (const glm::vec2& a : loop_) loopPsi_.push_back(polarAngle(a));
}

glm::vec2 EyeOpening::upperLid(float t) const {
  // Peak a little toward the nose, as on a real upper lid.
  const float bump = std::pow(std::max(0.0f, std::sin(std::numbers::pi_v<float> * std::pow(t, 0.82f))), 0.85f);
  return glm::mix(inner_, outer_, t) + glm::vec2(0.0f, upperHeight_ * bump);
}

glm::vec2 EyeOpening::lowerLid(float t) const {
  // Lowest point a little toward the outer corner.
  const float bump = std::pow(std::max(0.0f, std::sin(std::numbers::pi_v<float> * std::pow(t, 1.25f))), 0.9f);
  return glm::mix(inner_, outer_, t) - glm::vec2(0.0f, lowerDepth_ * bump);
}

glm::vec3 EyeOpening::direction(const glm::vec2& angles) const {
  const float a = radians(angles.x), b = radians(angles.y);
  return glm::vec3(side_ * std::sin(a) * std::cos(b), std::sin(b), std::cos(a) * std::cos(b));
}

glm::vec2 EyeOpening::angles(const glm::vec3& d) const {
  const glm::vec3 n = glm::normalize(d);
  return glm::vec2(degrees(std::atan2(side_ * n.x, n.z)), degrees(std::asin(std::clamp(n.y, -1.0f, 1.0f))));
}

float EyeOpening::polarAngle(const glm::vec2& a) const {
  const glm::vec2 q = (a - middle_) / halfExtent_;
  return std::atan2(q.y, q.x);
}

glm::vec2 EyeOpening::marginAt(float psi, bool* upper) const {
  // The loop's polar angles decrease monotonically from the inner corner
  // (angle ~pi) over the top to the outer corner (~0) and on around the
  // bottom; find the segment that brackets psi.
  const size_t n = loop_.size();
  auto wrapDiff = [](float a, float b) {  // a - b in (-pi, pi]
    float d = a - b;
    while (d > std::numbers::pi_v<float>) d -= 2 * std::numbers::pi_v<float>;
    while (d <= -std::numbers::pi_v<float>) d += 2 * std::numbers::pi_v<float>;
    return d;
  };
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const float di = wrapDiff(psi, loopPsi_[i]);
    const float dj = wrapDiff(psi, loopPsi_[j]);
    if ((di <= 0.0f && dj >= 0.0f) || (di >= 0.0f && dj <= 0.0f)) {
      const float span = di - dj;
      if (std::abs(span) > std::numbers::pi_v<float>) continue;  // the wrap-around, not a bracket
      const float t = std::abs(span) > 1e-12f ? di / span : 0.0f;
      if (upper) *upper = loopUpper_[i] && loopUpper_[j] ? true : (!loopUpper_[i] && !loopUpper_[j] ? false : t < 0.5f ? loopUpper_[i] : loopUpper_[j]);
      return glm::mix(loop_[i], loop_[j], t);
    }
  }
  if (upper) *upper = true;
  return middle_;
}

}  // namespace bake
