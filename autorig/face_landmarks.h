#pragma once
// The 68 facial landmarks of the iBUG 300-W layout (dlib's
// shape_predictor_68_face_landmarks), as points on a face's surface in the
// world space of its rest pose (autorig/posed_face.h):
//   0-16 jaw line (subject's right ear -> chin 8 -> left ear), 17-21 and 22-26
//   brows, 27-30 nose bridge, 31-35 nostrils, 36-41 and 42-47 eyes (36/39 and
//   42/45 the corners), 48-59 outer lips (48/54 corners), 60-67 inner lips.
// "Left"/"right" in the layout are the image's: point 36 is the subject's
// right eye's outer corner.
//
// A landmarks file (what a user writes when detection fails, or what the
// editor saves after points are moved):
//   {"landmarks68": [[x, y, z], ... 68 points], "source": "hand-placed"}
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "autorig/posed_face.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace autorig {

constexpr size_t kLandmarkCount = 68;

struct FaceLandmarks {
  std::array<glm::vec3, kLandmarkCount> points{};
  // Where they came from, for notes: "dlib (face box 215 px, confidence 1.55)",
  // or the file they were read from.
  std::string source;
};

// Errors name the file and the problem: not JSON, not 68 points, a point that
// is not three finite numbers (with its index).
eng::Result<FaceLandmarks> readLandmarksFile(const std::filesystem::path& path);
// Written whole (a .partial file renamed into place).
eng::Result<void> writeLandmarksFile(const FaceLandmarks& landmarks, const std::filesystem::path& path);

// Landmarks from a file are checked against the face they are for: each
// point within kOnSurfaceTolerance of the outer eye corners' distance from
// some triangle (the first one farther is named, with its distance), and the
// eye corners apart. Errors start with `source` (the file's name).
inline constexpr float kOnSurfaceTolerance = 0.05f;
eng::Result<void> checkLandmarksOnSurface(const FaceLandmarks& landmarks, const eng::Model& model,
                                          const PosedFace& posed, const std::string& source);

}  // namespace autorig
