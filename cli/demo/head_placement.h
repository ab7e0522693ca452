#pragma once
// Where the window demo's idle life moves one face's model. The life itself
// (sway, breathing, saccades, gaze on the eye targets) is the face's
// facial::Character; this adds where the model's head is:
//  - the sway turns the whole face about a neck point below its framing
//    bounds (transform()); a skinned avatar turns its head joint instead
//    (headTurn(), see app/skeleton_motion.h) and keeps only breathing();
//  - the breath lifts it by a fraction of its height;
//  - the eyes look at the viewer: gazeTarget() takes the camera in model
//    space and aims from the middle of the face's framing bounds, and
//    eyeOptions() places the eyes there for the character.
//
//   const HeadPlacement head(bounds, faceBounds);
//   auto character = facial::Character::create(parts, names, head.eyeOptions({.seed = seed}));
//   const glm::vec3 target = head.gazeTarget(cameraInModel);
//   (void)character->lookAt(target.x, target.y, target.z);
//   instance.transform = head.transform(placement, *character);
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/model.h"
#include "facial/character.h"

namespace cli {

class HeadPlacement {
 public:
  // bounds: what the view frames (the breath scales with its height, the
  // sway turns about a neck point below its centre); face: the head's
  // framing bounds (the eyes' place; `bounds` when invalid).
  HeadPlacement(const eng::Aabb& bounds, const eng::Aabb& face);

  // `options` with the eyes about a third of the head's width apart, either side of its middle.
  facial::CharacterOptions eyeOptions(facial::CharacterOptions options) const;
  // The viewer as the character's lookAt target (head space: from between the eyes).
  glm::vec3 gazeTarget(const glm::vec3& viewerInModel) const { return viewerInModel - eyes_; }

  // placement * sway about the neck * breathing lift.
  glm::mat4 transform(const glm::mat4& placement, const facial::Character& character) const;
  // placement * breathing lift, without the sway.
  glm::mat4 breathing(const glm::mat4& placement, const facial::Character& character) const;
  // The sway alone (yaw, nod, roll) and each eye's gaze as rotations in model-space axes.
  static glm::quat headTurn(const facial::Character& character);
  static glm::quat eyeTurn(const facial::Character& character, facial::Eye eye);

 private:
  glm::vec3 pivot_{0.0f};  // the neck
  glm::vec3 eyes_{0.0f};   // head-space origin, between the eyes
  glm::vec3 headSize_{1.0f};
  float height_ = 1.0f;
};

}  // namespace cli
