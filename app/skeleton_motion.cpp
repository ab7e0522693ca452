#include "app/skeleton_motion.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "engine/scene/posed_bounds.h"

namespace cli {

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

eng::Result<SkeletonMotion> SkeletonMotion::create(const eng::Model& model, const std::string& clip) {
  SkeletonMotion motion;
  motion.model_ = &model;
  if (!model.skins.empty()) motion.headJoint_ = eng::findHeadJoint(model);
  const std::string file = model.sourcePath.empty() ? std::string("the model") : model.sourcePath;
  if (clip == "all") {
    for (const eng::Animation& a : model.animations)
      if (!a.nodeChannels.empty()) motion.clips_.push_back(&a);
    if (motion.clips_.empty()) return eng::makeError(file + " has no skeletal clip (--clip all)");
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
      return eng::makeError(file + ": no skeletal clip '" + clip + "'; the file has: " + skeletalClipList(model));
    motion.clips_.push_back(found);
    motion.label_ = found->name;
  }
  for (const eng::Animation* a : motion.clips_) motion.duration_ = std::max(motion.duration_, a->duration());
  motion.rest_ = eng::restPose(model);
  motion.pose_ = motion.rest_;
  if (motion.active()) motion.update(0.0f);
  return motion;
}

void SkeletonMotion::update(float time, const glm::quat& headTurn) {
  if (!active()) return;
  pose_ = rest_;
  const float t = duration_ > 0.0f && std::isfinite(time) ? std::fmod(std::max(time, 0.0f), duration_) : 0.0f;
  for (const eng::Animation* clip : clips_) eng::sampleAnimation(*clip, t, pose_);
  eng::poseWorldMatrices(*model_, pose_, world_);
  if (headJoint_ < 0 || headTurn == glm::quat(1.0f, 0.0f, 0.0f, 0.0f) || model_->nodes[headJoint_].hasMatrix) return;
  // A turn in model-space axes about the joint, as a change of its local
  // rotation: local' = P^-1 * turn * P * local, P the parent's world rotation.
  const int parent = model_->nodes[headJoint_].parent;
  glm::quat parentRotation(1.0f, 0.0f, 0.0f, 0.0f);
  if (parent >= 0) {
    glm::mat3 m(world_[parent]);
    for (int c = 0; c < 3; ++c) m[c] = glm::normalize(m[c]);
    parentRotation = glm::quat_cast(m);
  }
  pose_.rotations[headJoint_] =
      glm::normalize(glm::inverse(parentRotation) * headTurn * parentRotation * pose_.rotations[headJoint_]);
  eng::poseWorldMatrices(*model_, pose_, world_);
}

}  // namespace cli
