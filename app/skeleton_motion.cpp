#include "app/skeleton_motion.h"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "engine/scene/posed_bounds.h"
#include "engine/scene/weights.h"
#include "facial/runtime/character/gaze_rig.h"

namespace app {

std::string skeletalClipList(const eng::Model& model) {
  std::string out;
  for (size_t i = 0; i < model.animations.size(); ++i) {
    const eng::Animation& a = model.animations[i];
    if (a.nodeChannels.empty()) continue;
    char duration[32];
    std::snprintf(duration, sizeof(duration), "%.1f s", a.duration());
    out += (out.empty() ? "" : ", ") + std::to_string(i) + " '" + a.name + "' (" + duration + ")";
  }
  return out.empty() ? "none" : out;
}

namespace {

// The eye joints (or, on an unskinned face, eye nodes) by name, left then
// right: LeftEye, EyeLeft, eye_L, Eye.L, L_Eye, mixamorig:LeftEye,
// J_Adj_L_FaceEye (VRoid), CC_Base_L_Eye; -1 where none.
std::array<int, 2> findEyeJoints(const eng::Model& model) {
  static constexpr std::string_view kNames[2][6] = {
      {"lefteye", "eyeleft", "eyel", "leye", "jadjlfaceeye", "ccbaseleye"},
      {"righteye", "eyeright", "eyer", "reye", "jadjrfaceeye", "ccbasereye"}};
  std::array<int, 2> found{-1, -1};
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    std::string_view name = model.nodes[n].name;
    if (const size_t colon = name.rfind(':'); colon != std::string_view::npos) name.remove_prefix(colon + 1);
    std::string key;
    for (char c : name)
      if (std::isalnum(static_cast<unsigned char>(c))) key.push_back(char(std::tolower(static_cast<unsigned char>(c))));
    for (int side = 0; side < 2; ++side)
      for (std::string_view candidate : kNames[side])
        if (found[size_t(side)] < 0 && key == candidate) found[size_t(side)] = int(n);
  }
  return found;
}

}  // namespace

eng::Result<SkeletonMotion> SkeletonMotion::create(const eng::Model& model, const std::string& clip) {
  SkeletonMotion motion;
  motion.model_ = &model;
  if (!model.skins.empty()) {
    motion.headJoint_ = eng::findHeadJoint(model);
    motion.eyeJoints_ = findEyeJoints(model);
  } else {
    // An unskinned face turns its eye nodes only when no morph target steers
    // the eyes (facecap has both: its eyeLook shapes already turn the balls).
    const std::vector<std::string> targets = eng::WeightLayout(model).names();
    if (!facial::GazeRig::create(targets).drivesWeights()) motion.eyeJoints_ = findEyeJoints(model);
  }
  const std::string file = model.sourcePath.empty() ? std::string("the model") : model.sourcePath;
  if (clip == "all") {
    for (const eng::Animation& a : model.animations)
      if (!a.nodeChannels.empty()) motion.clips_.push_back(&a);
    if (motion.clips_.empty()) return eng::makeError(eng::ErrorKind::NotFound, file + " has no skeletal clip (--clip all)");
    motion.label_ = "all " + std::to_string(motion.clips_.size()) + " clips";
  } else if (!clip.empty()) {
    const eng::Animation* found = nullptr;
    size_t index = 0;
    const auto [end, ec] = std::from_chars(clip.data(), clip.data() + clip.size(), index);
    if (ec == std::errc() && end == clip.data() + clip.size() && index < model.animations.size())
      found = &model.animations[index];
    for (const eng::Animation& a : model.animations)
      if (!found && a.name == clip) found = &a;
    if (!found || found->nodeChannels.empty())
      return eng::makeError(eng::ErrorKind::NotFound, file + ": no skeletal clip '" + clip + "'; the file has: " + skeletalClipList(model));
    motion.clips_.push_back(found);
    motion.label_ = found->name;
  }
  for (const eng::Animation* a : motion.clips_) motion.duration_ = std::max(motion.duration_, a->duration());
  motion.rest_ = eng::restPose(model);
  motion.pose_ = motion.rest_;
  if (motion.active()) motion.update(0.0f);
  return motion;
}

bool SkeletonMotion::turnJoint(int joint, const glm::quat& turn) {
  if (joint < 0 || turn == glm::quat(1.0f, 0.0f, 0.0f, 0.0f) || model_->nodes[joint].hasMatrix) return false;
  // A turn in model-space axes about the joint, as a change of its local
  // rotation: local' = P^-1 * turn * P * local, P the parent's world rotation.
  const int parent = model_->nodes[joint].parent;
  glm::quat parentRotation(1.0f, 0.0f, 0.0f, 0.0f);
  if (parent >= 0) {
    glm::mat3 m(world_[parent]);
    for (int c = 0; c < 3; ++c) m[c] = glm::normalize(m[c]);
    parentRotation = glm::quat_cast(m);
  }
  pose_.rotations[joint] = glm::normalize(glm::inverse(parentRotation) * turn * parentRotation * pose_.rotations[joint]);
  return true;
}

void SkeletonMotion::update(float time, const glm::quat& headTurn, const std::array<glm::quat, 2>& eyeTurns) {
  if (!active()) return;
  pose_ = rest_;
  const float t = duration_ > 0.0f && std::isfinite(time) ? std::fmod(std::max(time, 0.0f), duration_) : 0.0f;
  for (const eng::Animation* clip : clips_) eng::sampleAnimation(*clip, t, pose_);
  eng::poseWorldMatrices(*model_, pose_, world_);
  // The head first: the eyes turn in the head's new frame (their parents' world rotations).
  if (turnJoint(headJoint_, headTurn)) eng::poseWorldMatrices(*model_, pose_, world_);
  bool eyesMoved = false;
  for (int eye = 0; eye < 2; ++eye) eyesMoved |= turnJoint(eyeJoints_[size_t(eye)], eyeTurns[size_t(eye)]);
  if (eyesMoved) eng::poseWorldMatrices(*model_, pose_, world_);
}

}  // namespace app
