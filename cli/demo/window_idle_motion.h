#pragma once
// The window demo's idle life placed on one face. The life itself (sway,
// breathing, saccades, gaze) is the runtime's facial::CharacterLife, and which
// morph targets steer the eyes is facial::GazeRig (facial/runtime/character);
// this adds where the model's head is:
//  - the sway turns the whole face about a neck point below its framing
//    bounds (transform()); a skinned avatar turns its head joint instead
//    (headTurn(), see app/skeleton_motion.h) and keeps only breathing();
//  - the breath lifts it by a fraction of its height;
//  - the eyes look at the viewer: update() takes the camera in model space and
//    aims from the middle of the face's framing bounds.
// Each face gets its own phases and saccade stream from its seed. update() and
// applyGaze() do not allocate.
//
//   auto idle = IdleMotion::create(names, setup.vrm(), bounds, faceBounds, seed, still);
//   idle->update(dt, cameraInModel);
//   instance.transform = idle->transform(placement);
//   idle->applyGaze(weights);
#include <span>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/character/character_life.h"
#include "facial/runtime/character/gaze_rig.h"

namespace cli {

class IdleMotion {
 public:
  // bounds: what the view frames (amplitudes scale with its size, the sway
  // turns about a neck point below its centre); face: the head's framing
  // bounds (the eyes' place). still: no sway, breathing or saccades (the
  // eyes still follow the viewer).
  static eng::Result<IdleMotion> create(std::span<const std::string> targetNames, const facial::VrmExpressionSet* vrm,
                                        const eng::Aabb& bounds, const eng::Aabb& face, uint64_t seed, bool still);

  void update(float dt, const glm::vec3& viewerInModel);
  // placement * sway about the neck * breathing lift.
  glm::mat4 transform(const glm::mat4& placement) const;
  // The sway alone (yaw, nod, roll) as a rotation in model-space axes.
  glm::quat headTurn() const { return life_.headRotation(); }
  // Each eye's gaze as a rotation in model-space axes (for eye joints).
  glm::quat eyeTurn(facial::Eye eye) const { return life_.eyeRotation(eye); }
  // placement * breathing lift, without the sway.
  glm::mat4 breathing(const glm::mat4& placement) const;
  // Adds the current gaze to the targets that steer the eyes, clamped to [0,1] (no-op without them).
  void applyGaze(std::span<float> weights) const;
  bool hasGaze() const { return gaze_.drivesWeights(); }

 private:
  IdleMotion(facial::CharacterLife life, facial::GazeRig gaze) : life_(std::move(life)), gaze_(std::move(gaze)) {}

  facial::CharacterLife life_;
  facial::GazeRig gaze_;
  glm::vec3 pivot_{0.0f};      // the neck
  glm::vec3 eyes_{0.0f};       // head-space origin, between the eyes
  float size_ = 1.0f;
};

}  // namespace cli
