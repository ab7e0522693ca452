#pragma once
// Orbit camera framed from a model's bounds. glTF is +Y up and faces look
// toward +Z, so yaw = pitch = 0 looks at the face from the front (+Z).
// Matrices are for Vulkan: clip-space y down, depth 0..1.
#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace eng {

struct OrbitCamera {
  glm::vec3 target{0.0f};       // orbit centre
  float distance = 3.0f;        // from target at zoom 1
  float yawDegrees = 0.0f;      // + turns the camera toward +X (to the face's left side)
  float pitchDegrees = 0.0f;    // + looks from above
  float zoom = 1.0f;            // > 1 moves closer
  float fovYDegrees = 30.0f;
  float sceneRadius = 1.0f;     // bounding-sphere radius, for the clip planes
  // Where the orbit target lands in the image, in normalised device
  // coordinates (x right, y down, -1..1): a lens shift, so a face can sit in
  // the part of a window that UI panels leave free while the camera still
  // orbits the face. {0, 0} = the image centre.
  glm::vec2 imageCentre{0.0f};

  // Frames `bounds` (world space) so it fills most of an image of `aspect`
  // (width / height) seen from +Z.
  static OrbitCamera frame(const Aabb& bounds, float aspect = 1.0f, float fovYDegrees = 30.0f);

  glm::vec3 position() const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;

  // Moves `bounds`, as framed for the whole image of `imageSize`, into the
  // sub-rectangle [regionMin, regionMax] (pixels, y down), e.g. the part of a
  // window beside a panel: centres it there (imageCentre) and zooms out only
  // as far as the region's shape requires. Apply to a copy each frame.
  void fitToRegion(const Aabb& bounds, glm::vec2 imageSize, glm::vec2 regionMin, glm::vec2 regionMax);
  // Shows the sub-rectangle [regionMin, regionMax] of an image of imageSize
  // as a picture of the region's own size would show `bounds`: the camera
  // where frame(bounds, region aspect) puts it (then this camera's zoom, yaw
  // and pitch), the vertical field of view widened so that the region's
  // height spans fovYDegrees, the lens shifted to the region's centre. The
  // region is then that picture, pixel for pixel (an editor's view and
  // `facial play` at the region's size draw the same face; fitToRegion
  // instead keeps the whole image's framing, so its camera stands farther
  // off and the face's depth reads flatter). Apply to a copy each frame.
  void viewRegionAsImage(const Aabb& bounds, glm::vec2 imageSize, glm::vec2 regionMin, glm::vec2 regionMax);
};

}  // namespace eng
