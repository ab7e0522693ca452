#pragma once
// A VkImage with its own memory and one view over all its mips and layers.
#include <cstdint>
#include <utility>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

struct ImageDesc {
  VkExtent2D extent{0, 0};
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageUsageFlags usage = 0;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  uint32_t mipLevels = 1;
  uint32_t arrayLayers = 1;
  VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
  const char* debugName = "image";
};

class GpuImage {
 public:
  GpuImage() = default;
  GpuImage(GpuImage&&) noexcept = default;
  // View, then image, are destroyed before the memory is freed.
  GpuImage& operator=(GpuImage&& other) noexcept {
    if (this != &other) {
      view_.reset();
      image_.reset();
      desc_ = other.desc_;
      memory_ = std::move(other.memory_);
      image_ = std::move(other.image_);
      view_ = std::move(other.view_);
    }
    return *this;
  }
  static Result<GpuImage> create(const Context& ctx, const ImageDesc& desc);

  VkImage handle() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }
  const ImageDesc& desc() const { return desc_; }
  explicit operator bool() const { return static_cast<bool>(image_); }

 private:
  ImageDesc desc_;
  UniqueMemory memory_;  // declared first: freed after the image and its view
  UniqueImage image_;
  UniqueImageView view_;
};

// Records a layout transition / dependency for `mipCount` mips from `baseMip`, all layers.
struct ImageBarrier {
  VkImage image = VK_NULL_HANDLE;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageLayout newLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags srcStage = VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT;
  VkAccessFlags srcAccess = 0;
  VkPipelineStageFlags dstStage = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  VkAccessFlags dstAccess = 0;
  uint32_t baseMip = 0;
  uint32_t mipCount = VK_REMAINING_MIP_LEVELS;
};
void recordImageBarrier(VkCommandBuffer cmd, const ImageBarrier& barrier);

}  // namespace eng::vk
