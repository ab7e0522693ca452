#pragma once
// The life a character shows when nobody animates it: a slow head sway, breathing,
// eye saccades and where it looks (lookAt). The animation graph blinks (the `blink`
// node); this adds what is not a channel of the graph but a pose of the head and
// the eyes. Engine-agnostic outputs, all in head space (+X the face's own left,
// +Y up, +Z out of the face, origin between the eyes):
//   - headRotation(): the sway as a rotation of the head joint (skinned avatars)
//     or, about a neck point the caller picks, of the whole face;
//   - breathLift(): the chest's lift as a fraction of the character's height;
//   - eyeGaze(eye) / eyeRotation(eye): where each eye points, the lookAt target
//     (each eye aims at it from its own centre, so near targets converge) with
//     the saccades on top, clamped to that eye's limits. GazeRig turns the gaze
//     into morph weights (ARKit eyeLook*, FACS AU61-64, VRM lookAt expressions);
//     eyeRotation() is the eye joint's rotation for rigs with eye bones.
// Each character gets its own phases and saccade stream from its seed. Sized at
// create(); update() does not allocate.
//
//   auto life = facial::CharacterLife::create({.seed = id});
//   life->lookAt(cameraInHeadSpace);
//   life->update(dt);
//   gazeRig.apply(life->eyeGaze(facial::Eye::Left), life->eyeGaze(facial::Eye::Right), weights);
//   headJoint.rotation = life->headRotation() * headJoint.rotation;
#include <array>
#include <cstdint>
#include <optional>
#include <random>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/result.h"

namespace facial {

// The character's own left and right eye (its left is at +X in head space).
enum class Eye : uint8_t { Left, Right };

// One eye's direction: yaw > 0 turns toward the face's left (+X), pitch > 0 up. Radians.
struct EyeGaze {
  float yaw = 0.0f;
  float pitch = 0.0f;
};

// How far one eye turns from straight ahead, in degrees (human eyes: about
// 45 to the side, 25 up, 35 down; a stylised rig may allow less).
struct EyeLimits {
  float inward = 30.0f;   // toward the nose
  float outward = 35.0f;  // toward the ear
  float up = 25.0f;
  float down = 30.0f;
};

struct CharacterLifeOptions {
  uint64_t seed = 0;
  bool sway = true;      // head sway and breathing
  bool saccades = true;  // small quick eye moves around the lookAt target
  EyeLimits left;
  EyeLimits right;
  // Eye centres in head space, in the units lookAt targets are given in.
  glm::vec3 leftEye{0.032f, 0.0f, 0.0f};
  glm::vec3 rightEye{-0.032f, 0.0f, 0.0f};
};

class CharacterLife {
 public:
  // Errors: a limit that is negative, above 90 degrees or not finite; eye
  // centres that are not finite.
  static eng::Result<CharacterLife> create(const CharacterLifeOptions& options = {});

  // Both eyes aim at `target` (head space) from now on. Errors (nothing
  // changes): a non-finite coordinate.
  eng::Result<void> lookAt(const glm::vec3& target);
  // Back to looking straight ahead (the saccades go on).
  void lookAhead();
  std::optional<glm::vec3> lookAtTarget() const { return target_; }

  // Advances the sway, breathing and saccades by dt seconds. False (nothing
  // changes) for a negative or non-finite dt.
  bool update(float dt);

  // The sway (yaw, nod, roll) as a rotation in head-space axes; identity without sway.
  glm::quat headRotation() const;
  // The breath's lift, a fraction of the character's height (0 without sway).
  float breathLift() const;
  // Where `eye` points now: the lookAt direction plus the saccade, within its limits.
  EyeGaze eyeGaze(Eye eye) const;
  // eyeGaze(eye) as a rotation taking the eye's rest direction (+Z) to its gaze.
  glm::quat eyeRotation(Eye eye) const;
  // The saccade offset alone (yaw, pitch in radians), shared by both eyes.
  glm::vec2 saccade() const { return saccadeNow_; }

 private:
  CharacterLife() = default;
  void pickSaccade();
  float wave(float period, int phase) const;

  CharacterLifeOptions options_;
  std::optional<glm::vec3> target_;
  std::array<float, 5> phases_{};
  float time_ = 0.0f;
  glm::vec2 saccadeNow_{0.0f};
  glm::vec2 saccadeTarget_{0.0f};
  float nextSaccade_ = 0.0f;
  std::mt19937 random_;
};

// Clamps a gaze to the limits of `eye` (inward is toward -X for the left eye, +X for the right).
EyeGaze clampGaze(EyeGaze gaze, const EyeLimits& limits, Eye eye);

}  // namespace facial
