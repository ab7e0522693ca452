#include "engine/vk/draw/texture.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "engine/vk/device/buffer.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {
bool canBlitLinear(const Context& ctx, VkFormat format) {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), format, &props);
  constexpr VkFormatFeatureFlags kNeeded =
      VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (props.optimalTilingFeatures & kNeeded) == kNeeded;
}

// Textures are read by fragment shaders and, for MToon's outline width
// mask, by the outline pass's vertex shader.
constexpr VkPipelineStageFlags kSampledIn = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
}  // namespace

Result<GpuImage> createTexture(const Context& ctx, const TextureSource& source) {
  const size_t layerBytes = size_t{source.width} * source.height * 4;
  if (source.width == 0 || source.height == 0 || source.layers.empty())
    return makeError(ErrorKind::InvalidArgument, std::string("texture '") + source.debugName + "': empty (" + std::to_string(source.width) + "x" +
                     std::to_string(source.height) + ", " + std::to_string(source.layers.size()) + " layers)");
  for (size_t i = 0; i < source.layers.size(); ++i) {
    if (source.layers[i].size() != layerBytes)
      return makeError(ErrorKind::InvalidArgument, std::string("texture '") + source.debugName + "': layer " + std::to_string(i) + " has " +
                       std::to_string(source.layers[i].size()) + " bytes, expected " + std::to_string(layerBytes) +
                       " for " + std::to_string(source.width) + "x" + std::to_string(source.height) + " RGBA8");
  }
  const uint32_t layerCount = static_cast<uint32_t>(source.layers.size());
  const uint32_t mips =
      canBlitLinear(ctx, source.format) ? static_cast<uint32_t>(std::bit_width(std::max(source.width, source.height))) : 1u;

  ImageDesc desc;
  desc.extent = {source.width, source.height};
  desc.format = source.format;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.mipLevels = mips;
  desc.arrayLayers = layerCount;
  desc.viewType = source.viewType;
  desc.debugName = source.debugName;
  auto image = GpuImage::create(ctx, desc);
  if (!image) return image.error();

  auto staging = Buffer::create(ctx, layerBytes * layerCount, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                                "texture staging");
  if (!staging) return staging.error();
  for (uint32_t i = 0; i < layerCount; ++i)
    std::memcpy(staging->mapped() + layerBytes * i, source.layers[i].data(), layerBytes);

  VkImage img = image->handle();
  ENG_TRY(ctx.submitOneShot([&](VkCommandBuffer cmd) {
    recordImageBarrier(cmd, {img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT});
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, layerCount};
    copy.imageExtent = {source.width, source.height, 1};
    vkCmdCopyBufferToImage(cmd, staging->handle(), img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);

    // Each mip is blitted from the previous one, which is first made a transfer source.
    int32_t w = static_cast<int32_t>(source.width);
    int32_t h = static_cast<int32_t>(source.height);
    for (uint32_t mip = 1; mip < mips; ++mip) {
      recordImageBarrier(cmd, {img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                               VK_ACCESS_TRANSFER_READ_BIT, mip - 1, 1});
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 0, layerCount};
      blit.srcOffsets[1] = {w, h, 1};
      w = std::max(w / 2, 1);
      h = std::max(h / 2, 1);
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, layerCount};
      blit.dstOffsets[1] = {w, h, 1};
      vkCmdBlitImage(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                     &blit, VK_FILTER_LINEAR);
    }
    // All but the last mip are transfer sources now; the last is still a destination.
    if (mips > 1)
      recordImageBarrier(cmd, {img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                               VK_ACCESS_TRANSFER_READ_BIT, kSampledIn,
                               VK_ACCESS_SHADER_READ_BIT, 0, mips - 1});
    recordImageBarrier(cmd, {img, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_ACCESS_TRANSFER_WRITE_BIT, kSampledIn,
                             VK_ACCESS_SHADER_READ_BIT, mips - 1, 1});
  }));
  return image;
}

Result<UniqueSampler> createSampler(const Context& ctx, const TextureSampling& sampling) {
  const auto address = [](TextureWrap wrap) {
    return wrap == TextureWrap::ClampToEdge      ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
           : wrap == TextureWrap::MirroredRepeat ? VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT
                                                 : VK_SAMPLER_ADDRESS_MODE_REPEAT;
  };
  const auto filter = [](TextureFilter f) { return f == TextureFilter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; };
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter(sampling.magFilter);
  info.minFilter = filter(sampling.minFilter);
  info.mipmapMode =
      sampling.mipFilter == TextureFilter::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = address(sampling.wrapS);
  info.addressModeV = address(sampling.wrapT);
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  // Anisotropic filtering is nearly free on GPUs but llvmpipe emulates it at
  // a cost of seconds per frame; faces are seen head-on, so CPU devices skip
  // it. Without mipmaps (glTF's NEAREST / LINEAR minFilter) only level 0 is read.
  const bool cpuDevice = ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  info.anisotropyEnable = ctx.deviceInfo().samplerAnisotropy && !cpuDevice && sampling.mipmaps ? VK_TRUE : VK_FALSE;
  info.maxAnisotropy = std::min(8.0f, ctx.deviceInfo().properties.limits.maxSamplerAnisotropy);
  info.maxLod = sampling.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
  return UniqueSampler(ctx.device(), sampler);
}

}  // namespace eng::vk
