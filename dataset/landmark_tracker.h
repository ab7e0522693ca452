#pragma once
// The 68 iBUG landmarks of a face followed as its expression moves it: each
// rest-pose landmark (a point on the skin, autorig/face_landmarks.h) is tied
// once to the triangle it lies on, by barycentric coordinates, and re-evaluated
// on the MORPHED mesh for each set of weights: a raised brow lifts its brow
// points, an open jaw drops the chin and the lower lip. Then projected into
// the picture with the camera the image was drawn with.
//
//   auto tracker = dataset::LandmarkTracker::bind(face.model(), restLandmarks);
//   tracker->evaluate(weights, points);                      // world space, per item
//   auto pixels = dataset::projectLandmarks(points, camera, width, height);
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/view/camera.h"

namespace dataset {

using Landmarks3 = std::array<glm::vec3, autorig::kLandmarkCount>;
using Landmarks2 = std::array<glm::vec2, autorig::kLandmarkCount>;

class LandmarkTracker {
 public:
  // `model` must outlive the tracker. Each landmark binds to the nearest
  // triangle of the face's outer skin (autorig::outerSkinPrimitives); an
  // error names a landmark farther than `maxDistance` (model units) from it.
  static eng::Result<LandmarkTracker> bind(const eng::Model& model, const autorig::FaceLandmarks& rest,
                                           float maxDistance = 0.05f);

  // World-space landmarks of the model morphed by `weights` (flat,
  // eng::WeightLayout order) in its rest pose. No allocation.
  eng::Result<void> evaluate(std::span<const float> weights, Landmarks3& out) const;

 private:
  struct Corner {
    uint32_t vertex = 0;
    float weight = 0.0f;  // barycentric
  };
  struct Binding {
    uint32_t placement = 0;  // into placements_
    std::array<Corner, 3> corners{};
  };
  struct Placement {  // one drawn primitive the landmarks lie on
    const eng::Primitive* primitive = nullptr;
    uint32_t weightOffset = 0;  // its mesh's first flat weight
    glm::mat4 nodeWorld{1.0f};
    std::vector<glm::mat4> joints;  // empty: unskinned
  };
  glm::vec3 corner(const Placement& placement, uint32_t vertex, std::span<const float> weights) const;

  const eng::Model* model_ = nullptr;
  uint32_t weightCount_ = 0;
  std::vector<Placement> placements_;
  std::array<Binding, autorig::kLandmarkCount> bindings_{};
};

// Pixels (x right, y down, the image's top-left corner at 0, 0) of world
// points seen by `camera` in an image of width x height; a point behind the
// camera lands at (-1, -1).
Landmarks2 projectLandmarks(const Landmarks3& points, const eng::OrbitCamera& camera, uint32_t width, uint32_t height);

}  // namespace dataset
