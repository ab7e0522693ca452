#pragma once
// From a picture back to the mesh: a ray from the camera through a pixel,
// its nearest hit on the posed face's surface. The triangles are binned once
// by where they fall in the picture (a grid of cells), so each ray tests the
// few hundred triangles of its cell, not every triangle of a 100k-vertex head.
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/posed_face.h"
#include "engine/scene/model.h"

namespace autorig {

// The camera the picture was taken with: world to clip (Vulkan: y down,
// depth 0..1) and the picture's size in pixels.
struct PictureCamera {
  glm::mat4 viewProjection{1.0f};
  glm::vec2 imageSize{1.0f};
};

// Where a world point lands in the picture (pixels), nullopt behind the camera.
std::optional<glm::vec2> projectToPicture(const PictureCamera& camera, const glm::vec3& world);

struct SurfacePoint {
  size_t primitive = 0;  // index into PosedFace::primitives
  glm::vec3 position{0.0f};
  // True when the ray hit a triangle facing the camera; false when it fell
  // through a gap (an eye opening, parted lips) or just past an edge and a
  // vertex beside it was taken instead.
  bool hit = true;
};

class SurfaceCaster {
 public:
  // `cast`: one flag per PosedFace primitive, the ones rays may hit (the
  // skin; not eyeballs, teeth or hair). `model` (its triangles) and `posed`
  // must outlive the caster.
  SurfaceCaster(const eng::Model& model, const PosedFace& posed, const std::vector<bool>& cast,
                const PictureCamera& camera);

  // The surface seen at `pixel` (x right, y down, pixel centres at +0.5):
  // the nearest triangle facing the camera; where the ray meets the inside
  // of the head first, the nearest vertex (within `reachPixels` of it) of a
  // triangle facing the camera; where it meets nothing, the nearest vertex
  // within reach. Nullopt when nothing of the surface is that close.
  // A hit deeper than `maxDepth` (see depth()) counts as the inside too, and
  // no vertex deeper than it is taken: the rim of an opening whose inside
  // faces the camera (parted lips over a mouth's back wall).
  std::optional<SurfacePoint> cast(glm::vec2 pixel, float reachPixels,
                                   float maxDepth = std::numeric_limits<float>::infinity()) const;

  // How far behind the camera's near plane a world point lies, along the view.
  float depth(const glm::vec3& world) const { return glm::dot(world - nearCentre_, forward_); }

  std::optional<glm::vec2> project(const glm::vec3& world) const { return projectToPicture(camera_, world); }

 private:
  struct TriangleRef {
    uint32_t primitive;
    uint32_t triangle;
  };
  std::optional<SurfacePoint> nearestVertex(glm::vec2 pixel, float reachPixels, const glm::vec3* facing,
                                            float maxDepth) const;
  int cellOf(glm::vec2 pixel) const;

  const PosedFace* posed_;
  std::vector<const std::vector<uint32_t>*> indices_;  // per primitive, null when not cast
  std::vector<bool> outward_;                          // per primitive: counter-clockwise faces out
  PictureCamera camera_;
  glm::mat4 inverse_{1.0f};
  glm::vec3 nearCentre_{0.0f}, forward_{0, 0, -1};  // the picture centre's ray
  int cells_ = 64;  // per side
  std::vector<std::vector<TriangleRef>> bins_;
};

// The primitives rays should stop at: the outer surface of the face. Left
// out are those whose names say they are not skin (eyeballs, teeth, lashes,
// hair, glasses, clothes) and those that lie inside another primitive's box
// (an unnamed eyeball, the mouth's inside, brows over the skin):
// rays pass through to the skin behind them. All of them when that leaves none.
std::vector<bool> outerSkinPrimitives(const eng::Model& model, const PosedFace& posed);

// outerSkinPrimitives, and those it leaves out only for lying inside
// another's box that `camera` sees for the most part in front of everything
// else: a piece of the skin with a material of its own (the lips, a scan's
// texture chart, the nose), where the mouth's inside, an unnamed eyeball or
// teeth stay hidden behind the skin.
std::vector<bool> seenSkinPrimitives(const eng::Model& model, const PosedFace& posed, const PictureCamera& camera);

// The distance from `point` to the nearest triangle of the primitives flagged
// in `among` (all of them when empty); infinity when there are none.
float distanceToSurface(const eng::Model& model, const PosedFace& posed, const glm::vec3& point, const std::vector<bool>& among = {});

}  // namespace autorig
