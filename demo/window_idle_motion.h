#pragma once
// Idle life the animation graph does not give a face (the graph blinks):
// a slow head sway and breathing, as a small rotation/translation of the
// instance transform, and eye saccades on models with ARKit gaze targets
// (eyeLook{In,Out,Up,Down}{Left,Right} or _L/_R; nothing on other models).
// Each face gets its own phases and saccade stream from its seed. Sized in
// create(); update() and applyGaze() do not allocate.
//
//   auto idle = IdleMotion::create(setup.layout().names(), framingBounds(setup.model()), seed);
//   idle.update(dt);
//   instance.transform = idle.transform(placement);
//   idle.applyGaze(weights);
//
// A skinned avatar with a head joint turns only its head: the sway goes to
// the joint (headTurn(), see app/skeleton_motion.h) and the instance keeps
// just the breathing (breathing(placement)).
#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/model.h"

namespace cli {

// Flat target indices of the eight ARKit gaze targets, when a model has all of them.
struct GazeTargets {
  enum Slot { InLeft, OutLeft, UpLeft, DownLeft, InRight, OutRight, UpRight, DownRight, kCount };
  std::array<uint32_t, kCount> target{};

  // Matches "eyeLookInLeft", "eyeLookIn_L", "blendShape1.eyeLookIn_L" (case-insensitive).
  static bool find(std::span<const std::string> targetNames, GazeTargets& out);
};

class IdleMotion {
 public:
  // bounds: the model's framing bounds (amplitudes scale with its size, the
  // head turns about a neck point below its centre).
  static IdleMotion create(std::span<const std::string> targetNames, const eng::Aabb& bounds, uint64_t seed);

  void update(float dt);
  // placement * sway about the neck * breathing lift.
  glm::mat4 transform(const glm::mat4& placement) const;
  // The sway alone (yaw, nod, roll) as a rotation in model-space axes.
  glm::quat headTurn() const;
  // placement * breathing lift, without the sway.
  glm::mat4 breathing(const glm::mat4& placement) const;
  // Adds the current gaze to the gaze targets, clamped to [0,1] (no-op without them).
  void applyGaze(std::span<float> weights) const;
  bool hasGaze() const { return hasGaze_; }

 private:
  IdleMotion() = default;
  void pickSaccade();
  float wave(float period, int phase) const;
  float lift() const;

  bool hasGaze_ = false;
  GazeTargets gaze_;
  glm::vec3 pivot_{0.0f};
  float size_ = 1.0f;
  std::array<float, 5> phases_{};
  float time_ = 0.0f;
  glm::vec2 gazeNow_{0.0f};
  glm::vec2 gazeTarget_{0.0f};
  float nextSaccade_ = 0.0f;
  std::mt19937 random_;
};

}  // namespace cli
