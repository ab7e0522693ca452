#pragma once
// EXT_meshopt_compression and its Khronos successor KHR_meshopt_compression:
// buffer views whose bytes are stored meshopt-encoded in another buffer.
// Decoding writes the plain bytes into the view's own (parent) buffer, so the
// accessor reader and everything after it never know the file was compressed.
//
// Two steps around tinygltf: before parsing, "placeholder" buffers (a
// byteLength and no data, which tinygltf would refuse) get a tiny stand-in
// data: URI; after parsing they are sized to their byteLength and every
// compressed view is decoded into them.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <tiny_gltf.h>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"

namespace eng {

inline constexpr const char* kExtMeshopt = "EXT_meshopt_compression";
inline constexpr const char* kKhrMeshopt = "KHR_meshopt_compression";

// A buffer with no data of its own: only the uncompressed size of the views
// that decode into it.
struct MeshoptPlaceholder {
  int buffer = -1;
  size_t byteLength = 0;
};

// Finds the placeholder buffers of a parsed glTF document and gives each a
// stand-in data: URI so that tinygltf accepts it (see gltf_json_prepass.h).
// `glbHasBin`: in a GLB with a BIN chunk, buffer 0 without a uri is that chunk.
Result<std::vector<MeshoptPlaceholder>> stubMeshoptPlaceholders(nlohmann::json& doc, bool glbHasBin);

struct MeshoptDecodeStats {
  size_t views = 0;  // buffer views decoded
  bool usedExt = false, usedKhr = false;
};

// Sizes the placeholders and decodes every compressed buffer view into its
// parent buffer; the zero-filled placeholders and the decode scratch are
// charged to `budget`. Errors name the buffer view
// and what is wrong with it; they do not name the file (the caller does).
Result<MeshoptDecodeStats> decodeMeshoptViews(tinygltf::Model& gltf, const std::vector<MeshoptPlaceholder>& placeholders,
                                              LoadBudget& budget);

}  // namespace eng
