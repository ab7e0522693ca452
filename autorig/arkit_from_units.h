#pragma once
// The ARKit 52 shapes a face can have from the built-in head's action units,
// once those are on the face: each shape a sum of units, a bilateral unit
// split into its left and right halves by a smooth mask across the midline
// (the two halves add up to the unit), a unit of both lips into its upper and
// lower lip by a mask across the lip line; cheekSquint is AU6 away from the
// lids (eyeSquint, AU7, narrows the eye). The other direction of
// facial/runtime/rig/arkit_scheme.cpp (ARKit -> units). Gaze, cheek puff,
// dimples, mouth and jaw sideways and mouthClose have no unit to come from,
// and jawForward, mouthShrugUpper and mouthLowerDown match a real capture
// better made from the face: autorig/arkit_from_geometry.h makes those.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_frame.h"

namespace autorig {

// One target's world-space displacements over a fixed list of vertices.
struct NamedDeltas {
  std::string name;
  std::vector<glm::vec3> deltas;
};

// The unit named `name` over `vertices` vertices among `units`, or null.
const NamedDeltas* findUnit(std::span<const NamedDeltas> units, std::string_view name, size_t vertices);

// Shapes with ARKit's exact names (facial/runtime/rig/arkit_names.h), in
// ARKit's order, over the same vertices as `units` (positions: world space,
// at rest). A shape whose units are all missing is left out and named in
// `unmade`, as is every shape without a unit.
std::vector<NamedDeltas> arkitFromUnits(std::span<const NamedDeltas> units, std::span<const glm::vec3> positions,
                                        const LandmarkFrame& frame, std::vector<std::string>& unmade);

// A unit made back from ARKit shapes a face already has: each shape's
// canonical name and the share of it the unit is.
struct ShapeShare {
  std::string_view shape;
  float gain = 1.0f;
};

// How much of a shape's left half (the subject's left) reaches `p`: a smooth
// ramp across the midline, so the left and right halves of a unit add up to it.
float leftHalf(const glm::vec3& p, const LandmarkFrame& frame);

// The ARKit shapes that together are unit `unit` alone (its halves, or its
// upper and lower lip), as arkitFromUnits splits it: AU12_LipCornerPuller_L is
// mouthSmileLeft, AU4_BrowLowerer browDownLeft + browDownRight, AU26_JawDrop
// 0.6 of jawOpen (the share facial/runtime/rig/arkit_scheme.cpp drives
// jawOpen with), AU29 jawForward and AU16 the mouthLowerDown pair (made from
// the geometry, yet a face's own are these units). Empty for a unit no shape
// is made of alone (AU27, AU25).
std::vector<ShapeShare> shapesOfUnit(std::string_view unit);

}  // namespace autorig
