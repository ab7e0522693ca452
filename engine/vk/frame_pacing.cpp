#include "engine/vk/frame_pacing.h"

namespace eng::vk {

FrameAction decideFrameAction(VkExtent2D framebuffer, VkExtent2D swapchain, bool swapchainStale) {
  if (framebuffer.width == 0 || framebuffer.height == 0) return FrameAction::Skip;
  if (swapchainStale || framebuffer.width != swapchain.width || framebuffer.height != swapchain.height)
    return FrameAction::RecreateSwapchain;
  return FrameAction::Draw;
}

}  // namespace eng::vk
