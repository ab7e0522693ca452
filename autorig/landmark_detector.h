#pragma once
// dlib's face detector (HOG) and its 68-point shape predictor
// (shape_predictor_68_face_landmarks.dat, Debian libdlib-data, CC0) on an
// RGBA picture: the iBUG-68 points in pixels. The predictor's file is read
// once per process and path (it is 100 MB, about a second to load); the
// detector is shared behind a lock, so threads may call it.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace autorig {

inline constexpr const char* kDefaultShapePredictor = "/usr/share/dlib/shape_predictor_68_face_landmarks.dat";

// How far a face's eye line may be rolled before it is looked at level:
// in the picture (LandmarkDetector::detect turns the picture) and as the
// model is drawn (the finder stands the model up level).
inline constexpr float kLevelRollSlackDegrees = 10.0f;

// A pixel box: min and max corners, x right, y down.
struct PixelBox {
  glm::vec2 min{0.0f};
  glm::vec2 max{0.0f};
};

struct DetectedFace {
  std::array<glm::vec2, kLandmarkCount> pixels{};  // pixel centres at +0.5
  PixelBox box;
  // The detector's score (above 0 is a face; 1.5-3 on rendered heads), or
  // NaN when the box was given rather than found.
  float confidence = 0.0f;
};

class LandmarkDetector {
 public:
  // Errors: the predictor file is missing or not a dlib shape predictor.
  static eng::Result<std::shared_ptr<const LandmarkDetector>> shared(
      const std::filesystem::path& predictor = kDefaultShapePredictor);

  // The most confident face in `image`, or nullopt when there is none.
  std::optional<DetectedFace> detect(const eng::Image& image) const;
  // The 68 points inside a box known from elsewhere (the framing).
  DetectedFace fit(const eng::Image& image, const PixelBox& box) const;

  struct Impl;
  explicit LandmarkDetector(std::unique_ptr<Impl> impl);
  ~LandmarkDetector();

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace autorig
