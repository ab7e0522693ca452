#include "engine/vk/device/gpu_image.h"

#include <string>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<GpuImage> GpuImage::create(const Context& ctx, const ImageDesc& desc) {
  if (desc.extent.width == 0 || desc.extent.height == 0 || desc.mipLevels == 0 || desc.arrayLayers == 0)
    return makeError(ErrorKind::InvalidArgument, std::string("image '") + desc.debugName + "': empty extent " + std::to_string(desc.extent.width) +
                     "x" + std::to_string(desc.extent.height) + ", " + std::to_string(desc.mipLevels) + " mips, " +
                     std::to_string(desc.arrayLayers) + " layers");
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.extent.width, desc.extent.height, 1};
  info.mipLevels = desc.mipLevels;
  info.arrayLayers = desc.arrayLayers;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage raw = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateImage(ctx.device(), &info, nullptr, &raw));
  GpuImage img;
  img.desc_ = desc;
  img.image_ = UniqueImage(ctx.device(), raw);
  ctx.setObjectName(VK_OBJECT_TYPE_IMAGE, raw, desc.debugName);

  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device(), raw, &req);
  auto mem = ctx.allocate(req, MemoryUsage::GpuOnly);
  if (!mem) return mem.error().prefixed(std::string("image '") + desc.debugName + "': ");
  img.memory_ = std::move(mem->memory);
  ENG_VK_TRY(vkBindImageMemory(ctx.device(), raw, img.memory_.get(), 0));

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = raw;
  viewInfo.viewType = desc.viewType;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {desc.aspect, 0, desc.mipLevels, 0, desc.arrayLayers};
  VkImageView view = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
  img.view_ = UniqueImageView(ctx.device(), view);
  return img;
}

void recordImageBarrier(VkCommandBuffer cmd, const ImageBarrier& b) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = b.srcAccess;
  barrier.dstAccessMask = b.dstAccess;
  barrier.oldLayout = b.oldLayout;
  barrier.newLayout = b.newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = b.image;
  barrier.subresourceRange = {b.aspect, b.baseMip, b.mipCount, 0, VK_REMAINING_ARRAY_LAYERS};
  vkCmdPipelineBarrier(cmd, b.srcStage, b.dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace eng::vk
