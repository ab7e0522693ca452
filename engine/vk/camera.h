#pragma once
// Orbit camera framed from a model's bounds. glTF is +Y up and faces look
// toward +Z, so yaw = pitch = 0 looks at the face from the front (+Z).
// Matrices are for Vulkan: clip-space y down, depth 0..1.
#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace eng::vk {

struct OrbitCamera {
  glm::vec3 target{0.0f};       // orbit centre
  float distance = 3.0f;        // from target at zoom 1
  float yawDegrees = 0.0f;      // + turns the camera toward +X (to the face's left side)
  float pitchDegrees = 0.0f;    // + looks from above
  float zoom = 1.0f;            // > 1 moves closer
  float fovYDegrees = 30.0f;
  float sceneRadius = 1.0f;     // bounding-sphere radius, for the clip planes

  // Frames `bounds` (world space) so it fills most of an image of `aspect`
  // (width / height) seen from +Z.
  static OrbitCamera frame(const Aabb& bounds, float aspect = 1.0f, float fovYDegrees = 30.0f);

  glm::vec3 position() const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

}  // namespace eng::vk
