#pragma once
// CANDIDE-3's eyes. The mask models each eye as a patch of its own surface:
// the triangles between the lid margins are skin, so the rendered mask
// stares with blank skin where its eyes should be, and no expression that
// widens or narrows the eyes can read. The import cuts that patch out along
// the lid margins -- the vertices the "Eyes closed" unit moves (down: the
// upper lid, up: the lower lid) and the two corners that join them -- and
// puts a ball behind each opening, which the face dressing gives the
// procedural eye (importers/procedural_eyes.h). The lids stay in front of
// the ball, so "Eyes closed" still closes the eye over it.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace importers {

struct MaskEyeOpening {
  bool left = true;           // the subject's left (+x)
  std::vector<uint32_t> rim;  // closed loop of mesh edges: inner corner, upper lid, outer corner, lower lid
};

// Finds the openings from the "Eyes closed" deltas (one per vertex) and
// removes the triangles inside them from `indices` (a triangle list). Returns
// the openings cut, 0 to 2: one whose margins do not close into a loop of
// mesh edges, or whose inside is not a small patch, is left as it is.
std::vector<MaskEyeOpening> cutEyeOpenings(std::span<const glm::vec3> positions, std::vector<uint32_t>& indices,
                                       std::span<const glm::vec3> eyesClosed);

// A ball behind `opening` (a UV sphere, outward normals, counter-clockwise
// seen from outside): centred on the rim, a little wider than the opening so
// it fills it from any front view, set back until every rim vertex lies in
// front of it.
eng::Primitive eyeballBehind(std::span<const glm::vec3> positions, const MaskEyeOpening& opening);

// How `ball` (eyeballBehind's) follows an identity shape that moves the mask
// by `deltas` (one per mask vertex) at weight 1: it moves with the rim and
// grows as the opening's widest span does, about its front pole, so it still
// fills the opening from behind it.
eng::MorphTarget eyeballFollowing(std::span<const glm::vec3> positions, const MaskEyeOpening& opening,
                                  const eng::Primitive& ball, std::span<const glm::vec3> deltas);

}  // namespace importers
