#pragma once
// What tinygltf 2.7 refuses in compressed files, mended before it parses:
// meshopt placeholder buffers without data (gltf_meshopt.h) and Draco
// indices accessors without a bufferView (gltf_draco.h). Only files that
// mention those extensions are parsed twice; the rest pass untouched.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/gltf_meshopt.h"

namespace eng {

// `bytes` is a glTF JSON document or a GLB; when something had to be
// mended, `rewritten` receives the mended file (else it stays empty).
// Returns the meshopt placeholder buffers, to be sized after parsing.
Result<std::vector<MeshoptPlaceholder>> prepareCompressedGltf(std::span<const uint8_t> bytes, bool glb,
                                                              std::vector<uint8_t>& rewritten);

// Charges the objects a glTF JSON document declares (entries of its top-level
// arrays: materials, nodes, meshes, accessors, ...) at what tinygltf and the
// Model hold for each, before either is made: an empty `{}` entry costs three
// bytes of JSON and a full object in both. Scans the text without parsing it.
Result<void> chargeGltfObjects(std::string_view json, LoadBudget& budget);

}  // namespace eng
