#pragma once
// The 68 iBUG landmarks of a face found on its mesh (issue 33, step 1): the
// model rendered front-on headless (face framing; from the sides, above and
// below when the detector misses it, then stood in each other quarter-turn
// orientation, as a Z-up export or a head looking away in its file needs,
// then again from the face's own front when it is turned), dlib's detector and shape predictor run on the
// picture (autorig/landmark_detector.h), and each point
// cast from the camera back onto the face's outer skin
// (autorig/surface_cast.h).
//
//   autorig::PosedFace posed = autorig::poseAtRest(model);
//   auto landmarks = app::findFaceLandmarks(model, posed, {});
//   if (!landmarks) reporter.fail(landmarks.error());  // "no face found in any view of x.glb (...)"
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "autorig/face_landmarks.h"
#include "autorig/landmark_detector.h"
#include "autorig/posed_face.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace app {

struct FaceLandmarkOptions {
  uint32_t size = 640;  // the square picture's side, pixels
  std::filesystem::path predictor = autorig::kDefaultShapePredictor;
  std::string device;   // eng::vk::ContextOptions::device
  // What is drawn when it differs from the posed model (the dressed copy of
  // an untextured face, LoadedFace::displayModel()): same scene, same space.
  const eng::Model* display = nullptr;
  // When set, the picture with the detected points (green) and the cast
  // points seen from the same camera (red) is written there, for checking.
  std::filesystem::path picture;
};

// Errors, each naming the model's file: no face in any view, a point
// that falls off the surface, the predictor file missing, rendering failed.
// "+X", "-Z": a unit axis's name, for notes on how a file holds a face.
std::string signedAxisName(const glm::vec3& axis);
// "(0.70, 0.10, 0.71)": a direction between the axes, for the same notes.
std::string directionName(const glm::vec3& direction);
// The rotation that stands a face looking along `front` with its top along
// `top` (square unit axes) up: looking along +Z, its top along +Y.
glm::mat3 standingUpRotation(const glm::vec3& front, const glm::vec3& top);
// Seen level, a face's points look this many degrees up (autorig::
// LandmarkFrame::forward: its eyes are set back from its chin; 5-8° on the
// built-in head, facecap and the Ready Player Me avatar).
inline constexpr float kLevelPitchDegrees = 5.0f;
// The rotation that stands a face up exactly, from its points: looking
// along +Z, level (kLevelPitchDegrees), its eyes across X.
glm::mat3 levelRotation(const autorig::FaceLandmarks& landmarks);
// How a face's landmarks' source begins when no face was detected and the
// shape predictor was fitted in the box of the morph targets (a stylised
// face): its points place the features roughly, not the face's turn.
inline constexpr std::string_view kFittedInTheTargetsBox = "dlib's shape predictor in the box of the morph targets";

eng::Result<autorig::FaceLandmarks> findFaceLandmarks(const eng::Model& model, const autorig::PosedFace& posed,
                                                      const FaceLandmarkOptions& options = {});

}  // namespace app
