#pragma once
// The ARKit shapes no action unit of the built-in head gives, made from the
// face's own geometry once its units are made: the eight gaze shapes (each
// eyeball turned 30 degrees about its centre, the lids and the skin around
// the eye turned with it by a share that fades away from the eye, as a lid
// rides on the cornea), jawLeft / jawRight / jawForward (each vertex's share
// of the made jaw drop, shifted sideways or forward), mouthLeft / mouthRight, mouthClose (the lips
// brought back together over the made jaw drop, the chin left down),
// mouthShrugUpper (the upper lip pushed up as one piece), mouthLowerDown
// (a half of the lower lip drawn down and back),
// cheekPuff (the cheeks pushed out along their normals) and the dimples (the
// lip corners drawn back and out). Their amounts are in eye spans, as a real
// ARKit capture moves its face (facecap in ../shared/assets; the facecap
// ground-truth test measures each against facecap's own).
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/arkit_from_units.h"
#include "autorig/face_frame.h"
#include "autorig/face_landmarks.h"
#include "autorig/face_parts.h"

namespace autorig {

// The face the shapes are made on: one entry per vertex the units were made
// over (world space, at rest), and what each is.
struct ShapeGeometry {
  std::span<const glm::vec3> positions;
  std::span<const FacePart> parts;
  std::span<const glm::vec3> normals;  // outward, unit length; zero where not known (teeth, eyeballs)
  const FaceLandmarks* landmarks = nullptr;
  const LandmarkFrame* frame = nullptr;
  const FaceParts* faceParts = nullptr;  // eyeball centres
};

// Those of `wanted` (ARKit names) that this file can make, each over every
// vertex of `geometry`, in the order asked (a gaze shape turns its eye by
// facial::kArkitLookDegrees, the angle the runtime's gaze drives it with); the others are left in `unmade`
// (the gaze shapes where the face has no eyeballs of its own; the jaw's, the
// lips' made from its share and mouthClose where it has no jaw drop among
// `units`).
std::vector<NamedDeltas> arkitFromGeometry(std::span<const std::string> wanted, std::span<const NamedDeltas> units,
                                           const ShapeGeometry& geometry, std::vector<std::string>& unmade);

}  // namespace autorig
