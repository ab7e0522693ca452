#pragma once
// The window's swapchain: sRGB colour format, FIFO (vsync) or MAILBOX,
// images usable as transfer sources (screenshots). Recreated on resize.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class Swapchain {
 public:
  // `previous` (may be empty) is retired by the new one.
  static Result<Swapchain> create(const Context& ctx, VkExtent2D framebufferExtent, bool vsync,
                                  Swapchain* previous = nullptr);

  VkSwapchainKHR handle() const { return swapchain_.get(); }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  uint32_t minImageCount() const { return minImageCount_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkImageView view(uint32_t i) const { return views_[i].get(); }
  bool canCopyFrom() const { return transferSource_; }
  bool canBlitTo() const { return transferDestination_; }  // a scaled 3D view is blitted in

 private:
  UniqueSwapchain swapchain_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  uint32_t minImageCount_ = 2;
  bool transferSource_ = false;
  bool transferDestination_ = false;
  std::vector<VkImage> images_;  // owned by the swapchain
  std::vector<UniqueImageView> views_;
};

}  // namespace eng::vk
