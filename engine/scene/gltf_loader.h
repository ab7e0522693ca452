#pragma once
// glTF 2.0 import (.gltf with external or data: buffers, and .glb) into the
// CPU scene model. Every accessor is read with bounds checks of our own;
// external files are confined to the model's folder and never path-expanded.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// Limits that keep hostile files from allocating gigabytes. The defaults fit
// any real face model with room to spare (docs/reliability.md has what the
// shared assets cost).
struct GltfLoadLimits {
  size_t maxFileBytes = size_t{512} << 20;  // the .gltf/.glb and each external file
  // The load's one budget (engine/core/load_budget.h): everything the file's
  // numbers decide is charged to it before it is made: external files and
  // encoded images, the objects of its JSON arrays, meshopt fallback buffers
  // and scratch, Draco output, accessor data, derived normals and indices,
  // morph targets, decoded pixels.
  size_t maxDecodedBytes = kDefaultLoadBudgetBytes;
  size_t maxImagePixels = size_t{64} << 20;  // width * height of one decoded image
};

// Loads a .gltf or .glb (detected by content: the "glTF" magic, else JSON).
// Fatal problems come back as one-line errors naming the file; survivable
// ones (broken image, unsupported primitive mode) land in Model::warnings.
Result<Model> loadModel(const std::filesystem::path& path);
Result<Model> loadModel(const std::filesystem::path& path, const GltfLoadLimits& limits);
// The same over the file's bytes, already read (a caller that looked at them
// first need not read the file again). `path` names the file in messages, and
// its folder holds the external buffers and images of a .gltf. `charged`
// (when given) receives the bytes charged to the load's budget, even on failure.
Result<Model> loadModelFromBytes(std::span<const uint8_t> bytes, const std::filesystem::path& path,
                                 const GltfLoadLimits& limits = {}, size_t* charged = nullptr);

}  // namespace eng
