#pragma once
// The window's swapchain: sRGB colour format, FIFO (vsync) or MAILBOX,
// images usable as transfer sources (screenshots). Recreated on resize.
// Or, for a renderer that puts frames in the window itself (a CPU device's
// X11 shared-memory present), images of its own in the same role: no
// VkSwapchainKHR, image i is frame slot i's.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class Swapchain {
 public:
  // `previous` (may be empty) is retired by the new one.
  static Result<Swapchain> create(const Context& ctx, VkExtent2D framebufferExtent, bool vsync,
                                  Swapchain* previous = nullptr);
  // `count` images of `extent`, B8G8R8A8_SRGB (an X11 window's BGRX bytes), this renderer's own.
  static Result<Swapchain> createOwnImages(const Context& ctx, VkExtent2D extent, uint32_t count);
  bool ownImages() const { return !ownImages_.empty(); }

  VkSwapchainKHR handle() const { return swapchain_.get(); }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  uint32_t minImageCount() const { return minImageCount_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkImageView view(uint32_t i) const { return ownImages_.empty() ? views_[i].get() : ownImages_[i].view(); }
  bool canCopyFrom() const { return transferSource_; }
  bool canBlitTo() const { return transferDestination_; }  // a scaled 3D view is blitted in

 private:
  UniqueSwapchain swapchain_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  uint32_t minImageCount_ = 2;
  bool transferSource_ = false;
  bool transferDestination_ = false;
  std::vector<VkImage> images_;  // owned by the swapchain, or handles of ownImages_
  std::vector<GpuImage> ownImages_;
  std::vector<UniqueImageView> views_;
};

}  // namespace eng::vk
