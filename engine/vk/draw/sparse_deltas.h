#pragma once
// The sparse, vertex-major deltas of one primitive (morph.glsl), sliced:
// vertices go in slices of kMorphSliceLanes consecutive vertices, and a
// slice's k-th row holds the k-th entry of each of its vertices side by
// side, so the lanes that morph neighbouring vertices read neighbouring
// texels (a SIMD lane per vertex on a CPU device, a warp on a GPU) instead
// of one scattered entry list each. A vertex's entries are one per
// (vertex, target) pair that moves a position, normal or tangent or darkens
// a crease, in target order; a slice has as many rows as its busiest vertex
// has entries, the others padded with entries that add nothing.
// Layout: offsets[s] is slice s's first row (slices + 1 values); row r's
// planes follow each other, each kMorphSliceLanes texels, one per lane:
//   entries[(r * planes + plane) * kMorphSliceLanes + lane]
// planes: position delta + target index (as a float), normal delta + crease
// darkening, then the tangent delta where the primitive has tangent deltas.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace eng::vk {

inline constexpr uint32_t kMorphSliceLanes = 8;  // morph.glsl's MORPH_SLICE_LANES

struct SparseDeltas {
  std::vector<uint32_t> offsets;
  std::vector<glm::vec4> entries;
  bool hasNormals = false, hasTangents = false, hasCreases = false;
};

// Only the targets that carry deltas or darkening are visited, so the work is
// that of the data the targets hold (counted per vertex x target pair visited,
// work_counter.h): empty targets cost nothing, however many vertices there are.
SparseDeltas compactDeltas(const Primitive& prim);

}  // namespace eng::vk
