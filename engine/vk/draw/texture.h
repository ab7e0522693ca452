#pragma once
// RGBA8 textures (sRGB colour, or linear data such as a metallic-roughness
// map) with a full mip chain (generated on the GPU by blits), and the
// samplers that read them.
#include <cstdint>
#include <span>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

struct TextureSource {
  uint32_t width = 0;
  uint32_t height = 0;
  // One RGBA8 span per array layer, each width * height * 4 bytes.
  std::span<const std::span<const uint8_t>> layers;
  VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;  // or 2D_ARRAY
  const char* debugName = "texture";
  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;  // or R8G8B8A8_UNORM for data
};

// Ends in SHADER_READ_ONLY_OPTIMAL. Sizes are checked against the layer data.
Result<GpuImage> createTexture(const Context& ctx, const TextureSource& source);

// A sampler that reads such a texture as a glTF sampler asks (wrap modes,
// filters, whether mip levels are used).
Result<UniqueSampler> createSampler(const Context& ctx, const TextureSampling& sampling);

}  // namespace eng::vk
