#pragma once
// Eyebrows for a face that arrives without a skin texture. The brows carry
// half of what a face says -- raised and arched in surprise, oblique in
// sadness and fear, lowered and drawn together in anger -- and a plaster-white
// scan (facecap, many ARKit captures) has none: its brow targets move the
// skin, but at 256 px a moving patch of skin-coloured skin is invisible. So,
// for display only, face_dressing paints brows where anatomy puts them
// relative to the eyes: along the upper rim of each eye socket, from
// above the inner corner to past the outer corner, thicker at the head than
// the tail, arched at two thirds. The paint is attached to the skin (texture
// through the skin's UVs, or vertex colours when it has none), so every brow
// target moves it.
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"
#include "importers/procedural_eyes.h"

namespace importers {

// One eye's brow placement in the space of the mesh being painted.
struct BrowFrame {
  glm::vec3 eye{0.0f};      // eyeball centre
  glm::vec3 outward{1, 0, 0};  // toward this eye's outer corner
  glm::vec3 up{0, 1, 0};
  glm::vec3 forward{0, 0, 1};  // gaze
  float scale = 0.0f;          // distance between the eye centres: the unit brow shapes are given in
};

// The brow frames of a face with exactly two eyeballs, in the space of the
// mesh drawn by `skinNode` (node -1: model space); empty otherwise.
std::vector<BrowFrame> browFrames(const eng::Model& model, const std::vector<EyePrimitive>& eyes, int skinNode);

// Brow coverage in [0, 1] at rest-pose point `p` (same space as the frames).
float browCoverage(const std::vector<BrowFrame>& frames, const glm::vec3& p);

// The colour brows are painted with (linear).
glm::vec3 browColour();

}  // namespace importers
