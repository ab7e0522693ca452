#include "cli/demo/window_idle_motion.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace cli {

eng::Result<IdleMotion> IdleMotion::create(std::span<const std::string> targetNames, const facial::VrmExpressionSet* vrm,
                                           const eng::Aabb& bounds, const eng::Aabb& face, uint64_t seed, bool still) {
  const eng::Aabb& head = face.valid() ? face : bounds;
  const glm::vec3 headSize = head.valid() ? head.size() : glm::vec3(1.0f);
  facial::CharacterLifeOptions options{.seed = seed, .sway = !still, .saccades = !still};
  // The eyes sit about a third of the head's width apart, either side of its middle.
  options.leftEye = {0.16f * headSize.x, 0.0f, 0.0f};
  options.rightEye = {-0.16f * headSize.x, 0.0f, 0.0f};
  auto life = facial::CharacterLife::create(options);
  if (!life) return life.error();
  IdleMotion motion(std::move(*life), facial::GazeRig::create(targetNames, vrm));
  const glm::vec3 size = bounds.valid() ? bounds.size() : glm::vec3(1.0f);
  motion.size_ = std::max(size.y, 1e-6f);
  // The neck: centred, a fifth of the height below the bottom, a little behind the middle.
  motion.pivot_ = bounds.valid() ? glm::vec3(bounds.center().x, bounds.min.y - 0.2f * size.y,
                                             bounds.center().z - 0.15f * size.z)
                                 : glm::vec3(0.0f);
  motion.eyes_ = head.valid() ? head.center() : glm::vec3(0.0f);
  return motion;
}

void IdleMotion::update(float dt, const glm::vec3& viewerInModel) {
  // The viewer is always finite (an orbit camera); a refusal would only keep the last target.
  (void)life_.lookAt(viewerInModel - eyes_);
  life_.update(dt);
}

glm::mat4 IdleMotion::transform(const glm::mat4& placement) const {
  glm::mat4 m = glm::translate(placement, glm::vec3(0.0f, life_.breathLift() * size_, 0.0f) + pivot_);
  m *= glm::mat4_cast(life_.headRotation());
  return glm::translate(m, -pivot_);
}

glm::mat4 IdleMotion::breathing(const glm::mat4& placement) const {
  return glm::translate(placement, glm::vec3(0.0f, life_.breathLift() * size_, 0.0f));
}

void IdleMotion::applyGaze(std::span<float> weights) const {
  // Sizes were fixed at create() and the angles are clamped, so this cannot fail.
  (void)gaze_.apply(life_.eyeGaze(facial::Eye::Left), life_.eyeGaze(facial::Eye::Right), weights);
}

}  // namespace cli
