#pragma once
// glTF 2.0 export of the CPU scene model: .glb (one binary chunk) or .gltf
// (buffer as a data: URI), chosen by extension. Images are embedded as PNG,
// morph target names go to mesh.extras.targetNames, targets that move few
// vertices are written as sparse accessors, weights animations are kept and
// material detail layers go to material.extras.detailLayers.
#include <filesystem>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

Result<void> saveModel(const Model& model, const std::filesystem::path& path);

}  // namespace eng
