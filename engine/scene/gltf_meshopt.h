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
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

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

// Returns the placeholder buffers of a glTF JSON document or GLB (`bytes`);
// when there are any, `rewritten` receives the same file with each of them
// given a stand-in data: URI so that tinygltf accepts it. Files without
// meshopt buffers come back untouched (empty list, `rewritten` empty).
Result<std::vector<MeshoptPlaceholder>> stubMeshoptPlaceholders(std::span<const uint8_t> bytes, bool glb,
                                                                std::vector<uint8_t>& rewritten);

struct MeshoptDecodeStats {
  size_t views = 0;  // buffer views decoded
  bool usedExt = false, usedKhr = false;
};

// Sizes the placeholders (charged against `maxDecodedBytes`) and decodes every
// compressed buffer view into its parent buffer. Errors name the buffer view
// and what is wrong with it; they do not name the file (the caller does).
Result<MeshoptDecodeStats> decodeMeshoptViews(tinygltf::Model& gltf, const std::vector<MeshoptPlaceholder>& placeholders,
                                              size_t maxDecodedBytes);

}  // namespace eng
