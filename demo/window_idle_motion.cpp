#include "demo/window_idle_motion.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace cli {
namespace {

// "blendShape1.eyeLookIn_L" -> "eyelookinl": no prefix, no '_', lower case.
std::string normalisedTargetName(std::string_view name) {
  if (const size_t dot = name.rfind('.'); dot != std::string_view::npos) name.remove_prefix(dot + 1);
  std::string out;
  out.reserve(name.size());
  for (char c : name)
    if (c != '_') out.push_back(char(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

// Degrees of sway and the periods (seconds) it repeats at: slow and
// incommensurate, so the motion never visibly loops.
constexpr float kYawDegrees = 2.2f, kYawPeriod = 7.3f;
constexpr float kNodDegrees = 1.4f, kNodPeriod = 5.9f;
constexpr float kRollDegrees = 0.9f, kRollPeriod = 9.7f;
constexpr float kDriftDegrees = 0.8f, kDriftPeriod = 3.1f;
// Breathing: a lift of this fraction of the model's height, every few seconds.
constexpr float kBreathLift = 0.0035f, kBreathPeriod = 4.2f;
// Saccades: gaze range (target weight) and how fast the eyes get there.
constexpr float kGazeRangeX = 0.35f, kGazeRangeY = 0.2f, kSaccadeRate = 30.0f;

}  // namespace

bool GazeTargets::find(std::span<const std::string> targetNames, GazeTargets& out) {
  static constexpr const char* kDirections[] = {"in", "out", "up", "down"};
  static constexpr const char* kSides[][2] = {{"left", "l"}, {"right", "r"}};
  GazeTargets found;
  found.target.fill(UINT32_MAX);
  for (uint32_t i = 0; i < targetNames.size(); ++i) {
    const std::string name = normalisedTargetName(targetNames[i]);
    for (int side = 0; side < 2; ++side)
      for (int d = 0; d < 4; ++d)
        for (const char* suffix : kSides[side])
          if (name == std::string("eyelook") + kDirections[d] + suffix) found.target[side * 4 + d] = i;
  }
  if (std::find(found.target.begin(), found.target.end(), UINT32_MAX) != found.target.end()) return false;
  out = found;
  return true;
}

IdleMotion IdleMotion::create(std::span<const std::string> targetNames, const eng::Aabb& bounds, uint64_t seed) {
  IdleMotion motion;
  motion.hasGaze_ = GazeTargets::find(targetNames, motion.gaze_);
  const glm::vec3 size = bounds.valid() ? bounds.size() : glm::vec3(1.0f);
  motion.size_ = std::max(size.y, 1e-6f);
  // The neck: centred, a fifth of the height below the bottom, a little behind the middle.
  motion.pivot_ = bounds.valid() ? glm::vec3(bounds.center().x, bounds.min.y - 0.2f * size.y,
                                             bounds.center().z - 0.15f * size.z)
                                 : glm::vec3(0.0f);
  motion.random_.seed(uint32_t(seed * 0x9E3779B97F4A7C15ull >> 32));
  std::uniform_real_distribution<float> phase(0.0f, glm::two_pi<float>());
  for (float& p : motion.phases_) p = phase(motion.random_);
  motion.pickSaccade();
  return motion;
}

void IdleMotion::pickSaccade() {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> wait(0.4f, 2.6f);
  // Every third saccade or so returns to the viewer.
  gazeTarget_ = std::uniform_int_distribution<int>(0, 2)(random_) == 0
                    ? glm::vec2(0.0f)
                    : glm::vec2(unit(random_) * kGazeRangeX, unit(random_) * kGazeRangeY);
  nextSaccade_ = time_ + wait(random_);
}

void IdleMotion::update(float dt) {
  if (!(dt >= 0.0f) || !std::isfinite(dt)) return;
  time_ += dt;
  if (hasGaze_) {
    if (time_ >= nextSaccade_) pickSaccade();
    gazeNow_ += (gazeTarget_ - gazeNow_) * (1.0f - std::exp(-kSaccadeRate * dt));
  }
}

float IdleMotion::wave(float period, int phase) const {
  return std::sin(glm::two_pi<float>() * time_ / period + phases_[phase]);
}

float IdleMotion::lift() const { return kBreathLift * size_ * (0.5f + 0.5f * wave(kBreathPeriod, 4)); }

glm::quat IdleMotion::headTurn() const {
  const float yaw = kYawDegrees * wave(kYawPeriod, 0) + kDriftDegrees * wave(kDriftPeriod, 3);
  const float nod = kNodDegrees * wave(kNodPeriod, 1);
  const float roll = kRollDegrees * wave(kRollPeriod, 2);
  return glm::angleAxis(glm::radians(yaw), glm::vec3(0, 1, 0)) * glm::angleAxis(glm::radians(nod), glm::vec3(1, 0, 0)) *
         glm::angleAxis(glm::radians(roll), glm::vec3(0, 0, 1));
}

glm::mat4 IdleMotion::transform(const glm::mat4& placement) const {
  glm::mat4 m = glm::translate(placement, glm::vec3(0.0f, lift(), 0.0f) + pivot_);
  m *= glm::mat4_cast(headTurn());
  return glm::translate(m, -pivot_);
}

glm::mat4 IdleMotion::breathing(const glm::mat4& placement) const {
  return glm::translate(placement, glm::vec3(0.0f, lift(), 0.0f));
}

void IdleMotion::applyGaze(std::span<float> weights) const {
  if (!hasGaze_) return;
  // +x: toward the face's left (+X), where the left eye looks out and the right eye in.
  const float toLeft = std::max(gazeNow_.x, 0.0f), toRight = std::max(-gazeNow_.x, 0.0f);
  const float up = std::max(gazeNow_.y, 0.0f), down = std::max(-gazeNow_.y, 0.0f);
  const std::array<float, GazeTargets::kCount> add{toRight, toLeft, up, down, toLeft, toRight, up, down};
  for (int slot = 0; slot < GazeTargets::kCount; ++slot) {
    const uint32_t t = gaze_.target[slot];
    if (t < weights.size()) weights[t] = std::clamp(weights[t] + add[slot], 0.0f, 1.0f);
  }
}

}  // namespace cli
