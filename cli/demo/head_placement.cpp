#include "cli/demo/head_placement.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace cli {

namespace {

glm::quat quatFromXyzw(const std::array<float, 4>& xyzw) { return glm::quat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]); }

}  // namespace

HeadPlacement::HeadPlacement(const eng::Aabb& bounds, const eng::Aabb& face) {
  const eng::Aabb& head = face.valid() ? face : bounds;
  headSize_ = head.valid() ? head.size() : glm::vec3(1.0f);
  const glm::vec3 size = bounds.valid() ? bounds.size() : glm::vec3(1.0f);
  height_ = std::max(size.y, 1e-6f);
  // The neck: centred, a fifth of the height below the bottom, a little behind the middle.
  pivot_ = bounds.valid() ? glm::vec3(bounds.center().x, bounds.min.y - 0.2f * size.y, bounds.center().z - 0.15f * size.z)
                          : glm::vec3(0.0f);
  eyes_ = head.valid() ? head.center() : glm::vec3(0.0f);
}

facial::CharacterOptions HeadPlacement::eyeOptions(facial::CharacterOptions options) const {
  options.leftEye = {0.16f * headSize_.x, 0.0f, 0.0f};
  options.rightEye = {-0.16f * headSize_.x, 0.0f, 0.0f};
  return options;
}

glm::mat4 HeadPlacement::transform(const glm::mat4& placement, const facial::Character& character) const {
  glm::mat4 m = glm::translate(placement, glm::vec3(0.0f, character.breathLift() * height_, 0.0f) + pivot_);
  m *= glm::mat4_cast(headTurn(character));
  return glm::translate(m, -pivot_);
}

glm::mat4 HeadPlacement::breathing(const glm::mat4& placement, const facial::Character& character) const {
  return glm::translate(placement, glm::vec3(0.0f, character.breathLift() * height_, 0.0f));
}

glm::quat HeadPlacement::headTurn(const facial::Character& character) { return quatFromXyzw(character.headRotation()); }

glm::quat HeadPlacement::eyeTurn(const facial::Character& character, facial::Eye eye) {
  return quatFromXyzw(character.eyeRotation(eye));
}

}  // namespace cli
