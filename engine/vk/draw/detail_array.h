#pragma once
// A material's detail layers as one sRGB 2D-array texture (layer i = detail
// layer i), so a material can have any number of layers with one binding.
// Layers of different sizes are resampled (gamma-correct) to the largest.
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"

namespace eng::vk {

// material.detailLayers must be non-empty and reference valid, non-empty images.
Result<GpuImage> createDetailArray(const Context& ctx, const Model& model, const Material& material);

}  // namespace eng::vk
