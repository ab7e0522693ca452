#pragma once
// Structural consistency of a Model built by hand or by an importer: every
// array has the length the others imply, every index points somewhere and
// every number is finite. The one validator of a Model: the glTF writer
// refuses models that fail it (so a file we write always loads), the OBJ
// importer checks what it built, and GpuModel::create checks with
// ModelCheck::gpuUpload() before anything reaches the device.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// What a use of the model needs beyond consistency. The defaults are what
// any consistent model satisfies (what a glTF file may leave out).
struct ModelCheck {
  // Every primitive has one normal per vertex. glTF allows none (readers
  // generate them, ours does at load); the GPU's vertex buffer has a normal
  // per vertex and the renderer does not generate them.
  bool requireNormals = false;
  // Every primitive is a non-empty indexed triangle list. glTF allows a
  // primitive without indices (or an empty one); the renderer draws indexed.
  bool requireIndices = false;
  // The most vertices one primitive may have. The renderer counts a
  // primitive's vertices, and the few vec4s it keeps per vertex, in 32 bits.
  size_t maxVertices = std::numeric_limits<size_t>::max();

  // What GpuModel::create asks of a model before uploading it.
  static constexpr ModelCheck gpuUpload() {
    return {.requireNormals = true, .requireIndices = true, .maxVertices = std::numeric_limits<uint32_t>::max() / 4};
  }
};

// The first problem found, kind Malformed, as one line naming the element
// (image, material, mesh and primitive, morph target, node, skin, animation
// channel) and the sizes that disagree. The caller puts the file in front.
Result<void> checkModel(const Model& model, const ModelCheck& needs = {});

}  // namespace eng
