#pragma once
// The skeleton of a face in `facial play` and the demo: an optional skeletal
// clip of the file, looping, plus an idle turn of the head joint (sway, nods)
// for skinned avatars, where turning the whole model would swing the body
// too, and the gaze of the eye joints. Faces without a skin, a clip or eye
// nodes to turn have nothing to pose: nodeWorld() stays empty and the
// renderer draws the rest pose.
//
//   auto skeleton = SkeletonMotion::create(model, "Dance");   // or "3", "all", ""
//   skeleton->update(time, idleHeadTurn);
//   instance.nodeWorld = skeleton->nodeWorld();
#include <array>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/scene/skeleton_pose.h"

namespace app {

class SkeletonMotion {
 public:
  // clip: "" none; an animation's name; its index; "all" every skeletal clip
  // at once (files that split one motion into a clip per joint, like
  // CesiumMan). A clip that does not exist or moves no node is an error
  // listing the clips. The model must outlive the object.
  static eng::Result<SkeletonMotion> create(const eng::Model& model, const std::string& clip);

  // Whether the head turn goes to a joint (skinned model with a head joint).
  bool turnsHeadJoint() const { return headJoint_ >= 0; }
  int headJoint() const { return headJoint_; }
  // The eye joints (left, right: the face's own sides), -1 each where there is
  // none (named LeftEye / EyeLeft / eye_L / J_Adj_L_FaceEye / ...). On an
  // unskinned face these are the nodes that carry the eyeballs (the built-in
  // head's EyeLeft / EyeRight), unless its morph targets steer the eyes.
  const std::array<int, 2>& eyeJoints() const { return eyeJoints_; }
  // Whether there is a pose to upload (a clip, a head joint or an eye joint).
  bool active() const { return !clips_.empty() || headJoint_ >= 0 || eyeJoints_[0] >= 0 || eyeJoints_[1] >= 0; }
  float clipDuration() const { return duration_; }
  std::string clipLabel() const { return label_; }

  // The pose at `time` seconds (clips loop), with the head joint turned by
  // `headTurn` about its own position, in model-space axes, and each eye
  // joint by its gaze (eyeTurns: left, right; facial::CharacterLife::eyeRotation).
  void update(float time, const glm::quat& headTurn = glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
              const std::array<glm::quat, 2>& eyeTurns = {glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
                                                          glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
  // Every node's model-space matrix after update(); empty when !active().
  std::span<const glm::mat4> nodeWorld() const { return world_; }

 private:
  const eng::Model* model_ = nullptr;
  std::vector<const eng::Animation*> clips_;
  float duration_ = 0.0f;
  std::string label_;
  // Turns `joint` by `turn` (model-space axes) about its own position; true when it moved.
  bool turnJoint(int joint, const glm::quat& turn);

  int headJoint_ = -1;
  std::array<int, 2> eyeJoints_{-1, -1};
  eng::Pose rest_;
  eng::Pose pose_;
  std::vector<glm::mat4> world_;
};

// Lists the model's skeletal clips for messages: "0 'Dance' (2.1 s), 1 ...".
std::string skeletalClipList(const eng::Model& model);

}  // namespace app
