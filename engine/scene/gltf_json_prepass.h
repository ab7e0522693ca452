#pragma once
// What tinygltf 2.7 refuses in compressed files, mended before it parses:
// meshopt placeholder buffers without data (gltf_meshopt.h) and Draco
// indices accessors without a bufferView (gltf_draco.h). Only files that
// mention those extensions are parsed twice; the rest pass untouched.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/gltf_meshopt.h"

namespace eng {

// `bytes` is a glTF JSON document or a GLB; when something had to be
// mended, `rewritten` receives the mended file (else it stays empty).
// Returns the meshopt placeholder buffers, to be sized after parsing.
Result<std::vector<MeshoptPlaceholder>> prepareCompressedGltf(std::span<const uint8_t> bytes, bool glb,
                                                              std::vector<uint8_t>& rewritten);

}  // namespace eng
