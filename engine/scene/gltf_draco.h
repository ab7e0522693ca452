#pragma once
// KHR_draco_mesh_compression: a primitive's indices and attributes stored as
// one Draco bitstream. Decoding appends the plain data as a new buffer and
// points the primitive's accessors at it, so the rest of the loader reads
// them like any other accessor (with the same bounds checks).
#include <cstddef>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"

namespace eng {

inline constexpr const char* kKhrDraco = "KHR_draco_mesh_compression";

// Before tinygltf: it refuses an indices accessor without a bufferView, which
// is how Draco primitives without fallback data declare theirs. Such
// accessors borrow the primitive's Draco bufferView until the decoder points
// them at the decoded indices. Returns whether the document changed.
bool stubDracoIndices(nlohmann::json& doc);

// Decodes every Draco-compressed primitive; returns how many. Decoded bytes
// are charged to `budget`. Errors name the mesh and primitive
// but not the file (the caller adds it).
Result<size_t> decodeDracoPrimitives(tinygltf::Model& gltf, LoadBudget& budget);

}  // namespace eng
