#include "engine/view/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace eng {

OrbitCamera OrbitCamera::frame(const Aabb& bounds, float aspect, float fovYDegrees) {
  OrbitCamera camera;
  camera.fovYDegrees = fovYDegrees;
  if (!bounds.valid()) return camera;
  const glm::vec3 half = bounds.size() * 0.5f;
  camera.target = bounds.center();
  camera.sceneRadius = std::max(glm::length(half), 1e-6f);
  // Fit the box's front face (seen from +Z) in the image with a small
  // margin, then step back by half the depth so the nearest point fits too.
  // Tighter than a bounding sphere: a head fills the frame instead of floating in it.
  const float tanHalf = std::tan(glm::radians(fovYDegrees) * 0.5f);
  const float margin = 1.05f;
  const float fit = std::max(half.y, half.x / std::max(aspect, 1e-3f)) * margin / tanHalf;
  camera.distance = std::max(fit + half.z, camera.sceneRadius * 1.05f);
  return camera;
}

glm::vec3 OrbitCamera::position() const {
  const float yaw = glm::radians(yawDegrees);
  const float pitch = glm::radians(std::clamp(pitchDegrees, -89.0f, 89.0f));
  const glm::vec3 dir{std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch)};
  return target + dir * (distance / std::max(zoom, 1e-3f));
}

glm::mat4 OrbitCamera::view() const { return glm::lookAtRH(position(), target, glm::vec3(0.0f, 1.0f, 0.0f)); }

glm::mat4 OrbitCamera::projection(float aspect) const {
  const float d = distance / std::max(zoom, 1e-3f);
  const float nearPlane = std::max(d - sceneRadius * 1.5f, d * 0.01f);
  const float farPlane = d + sceneRadius * 1.5f;
  glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(fovYDegrees), aspect, nearPlane, farPlane);
  p[1][1] *= -1.0f;  // Vulkan clip space: +y points down
  // Lens shift: clip.xy gains -imageCentre * clip.w (clip.w = -z_view), so
  // every point moves by imageCentre in NDC and perspective is unchanged.
  p[2][0] -= imageCentre.x;
  p[2][1] -= imageCentre.y;
  return p;
}

void OrbitCamera::fitToRegion(const Aabb& bounds, glm::vec2 imageSize, glm::vec2 regionMin, glm::vec2 regionMax) {
  if (!(imageSize.x >= 1.0f) || !(imageSize.y >= 1.0f)) return;
  const glm::vec2 lo = glm::clamp(regionMin, glm::vec2(0.0f), imageSize - 1.0f);
  const glm::vec2 hi = glm::clamp(regionMax, lo + 1.0f, imageSize);
  const glm::vec2 region = hi - lo;
  // Distance that fits the bounds into a full-height image of the region's
  // shape, scaled to the region's height; relative to the whole image's fit.
  const OrbitCamera whole = frame(bounds, imageSize.x / imageSize.y, fovYDegrees);
  const OrbitCamera inRegion = frame(bounds, region.x / region.y, fovYDegrees);
  zoom *= std::min(1.0f, whole.distance * region.y / (inRegion.distance * imageSize.y));
  imageCentre = (lo + hi) / imageSize - 1.0f;
}

void OrbitCamera::viewRegionAsImage(const Aabb& bounds, glm::vec2 imageSize, glm::vec2 regionMin, glm::vec2 regionMax) {
  if (!(imageSize.x >= 1.0f) || !(imageSize.y >= 1.0f)) return;
  const glm::vec2 lo = glm::clamp(regionMin, glm::vec2(0.0f), imageSize - 1.0f);
  const glm::vec2 hi = glm::clamp(regionMax, lo + 1.0f, imageSize);
  const glm::vec2 region = hi - lo;
  distance = frame(bounds, region.x / region.y, fovYDegrees).distance;
  const float tanHalf = std::tan(glm::radians(fovYDegrees) * 0.5f) * imageSize.y / region.y;
  fovYDegrees = glm::degrees(2.0f * std::atan(tanHalf));
  imageCentre = (lo + hi) / imageSize - 1.0f;
}

}  // namespace eng
