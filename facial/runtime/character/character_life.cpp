#include "facial/runtime/character/character_life.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

namespace facial {
namespace {

// Degrees of sway and the periods (seconds) it repeats at: slow and
// incommensurate, so the motion never visibly loops.
constexpr float kYawDegrees = 2.2f, kYawPeriod = 7.3f;
constexpr float kNodDegrees = 1.4f, kNodPeriod = 5.9f;
constexpr float kRollDegrees = 0.9f, kRollPeriod = 9.7f;
constexpr float kDriftDegrees = 0.8f, kDriftPeriod = 3.1f;
// Breathing: a lift of this fraction of the character's height, every few seconds.
constexpr float kBreathLift = 0.0035f, kBreathPeriod = 4.2f;
// Saccades: how far from the target the eyes jump (degrees) and how fast they get there (1/s).
constexpr float kSaccadeYawDegrees = 10.5f, kSaccadePitchDegrees = 6.0f, kSaccadeRate = 30.0f;

bool validLimits(const EyeLimits& l) {
  for (float v : {l.inward, l.outward, l.up, l.down})
    if (!std::isfinite(v) || v < 0.0f || v > 90.0f) return false;
  return true;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The direction from `eye` to `target` as yaw / pitch; straight ahead when they coincide.
EyeGaze aim(const glm::vec3& eye, const glm::vec3& target) {
  const glm::vec3 d = target - eye;
  const float horizontal = std::sqrt(d.x * d.x + d.z * d.z);
  if (horizontal < 1e-9f && std::abs(d.y) < 1e-9f) return {};
  return {std::atan2(d.x, d.z), std::atan2(d.y, horizontal)};
}

}  // namespace

EyeGaze clampGaze(EyeGaze gaze, const EyeLimits& limits, Eye eye) {
  // +yaw (toward +X) is outward for the left eye, inward for the right one.
  const float towardPlusX = glm::radians(eye == Eye::Left ? limits.outward : limits.inward);
  const float towardMinusX = glm::radians(eye == Eye::Left ? limits.inward : limits.outward);
  gaze.yaw = std::clamp(gaze.yaw, -towardMinusX, towardPlusX);
  gaze.pitch = std::clamp(gaze.pitch, -glm::radians(limits.down), glm::radians(limits.up));
  return gaze;
}

eng::Result<CharacterLife> CharacterLife::create(const CharacterLifeOptions& options) {
  if (!validLimits(options.left) || !validLimits(options.right))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "character life: eye limits must be finite degrees in [0, 90]");
  if (!finite(options.leftEye) || !finite(options.rightEye))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "character life: eye centres must be finite");
  CharacterLife life;
  life.options_ = options;
  life.random_.seed(uint32_t(options.seed * 0x9E3779B97F4A7C15ull >> 32));
  std::uniform_real_distribution<float> phase(0.0f, glm::two_pi<float>());
  for (float& p : life.phases_) p = phase(life.random_);
  life.pickSaccade();
  return life;
}

eng::Result<void> CharacterLife::lookAt(const glm::vec3& target) {
  if (!finite(target))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "lookAt: target (" + std::to_string(target.x) + ", " + std::to_string(target.y) + ", " +
                          std::to_string(target.z) + ") is not finite");
  target_ = target;
  return {};
}

void CharacterLife::lookAhead() { target_.reset(); }

void CharacterLife::pickSaccade() {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> wait(0.4f, 2.6f);
  // Every third saccade or so returns to the target itself.
  const float x = glm::radians(kSaccadeYawDegrees), y = glm::radians(kSaccadePitchDegrees);
  saccadeTarget_ = std::uniform_int_distribution<int>(0, 2)(random_) == 0
                       ? glm::vec2(0.0f)
                       : glm::vec2(unit(random_) * x, unit(random_) * y);
  nextSaccade_ = time_ + wait(random_);
}

bool CharacterLife::update(float dt) {
  if (!(dt >= 0.0f) || !std::isfinite(dt)) return false;
  time_ += dt;
  if (options_.saccades) {
    if (time_ >= nextSaccade_) pickSaccade();
    saccadeNow_ += (saccadeTarget_ - saccadeNow_) * (1.0f - std::exp(-kSaccadeRate * dt));
  }
  return true;
}

float CharacterLife::wave(float period, int phase) const {
  return std::sin(glm::two_pi<float>() * time_ / period + phases_[size_t(phase)]);
}

glm::quat CharacterLife::headRotation() const {
  if (!options_.sway) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  const float yaw = kYawDegrees * wave(kYawPeriod, 0) + kDriftDegrees * wave(kDriftPeriod, 3);
  const float nod = kNodDegrees * wave(kNodPeriod, 1);
  const float roll = kRollDegrees * wave(kRollPeriod, 2);
  return glm::angleAxis(glm::radians(yaw), glm::vec3(0, 1, 0)) * glm::angleAxis(glm::radians(nod), glm::vec3(1, 0, 0)) *
         glm::angleAxis(glm::radians(roll), glm::vec3(0, 0, 1));
}

float CharacterLife::breathLift() const {
  return options_.sway ? kBreathLift * (0.5f + 0.5f * wave(kBreathPeriod, 4)) : 0.0f;
}

EyeGaze CharacterLife::eyeGaze(Eye eye) const {
  EyeGaze gaze = target_ ? aim(eye == Eye::Left ? options_.leftEye : options_.rightEye, *target_) : EyeGaze{};
  gaze.yaw += saccadeNow_.x;
  gaze.pitch += saccadeNow_.y;
  return clampGaze(gaze, eye == Eye::Left ? options_.left : options_.right, eye);
}

glm::quat CharacterLife::eyeRotation(Eye eye) const {
  const EyeGaze gaze = eyeGaze(eye);
  // Yaw about +Y takes +Z toward +X; pitching up takes +Z toward +Y, a turn about -X.
  return glm::angleAxis(gaze.yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(-gaze.pitch, glm::vec3(1, 0, 0));
}

}  // namespace facial
