#pragma once
// What the window loop does with the next frame, from the window's current
// framebuffer size and the swapchain's state. Pure, so resize and minimise
// handling is testable without a window system.
#include <vulkan/vulkan.h>

namespace eng::vk {

enum class FrameAction {
  Skip,                // minimised (0x0): nothing to draw into; wait for events
  RecreateSwapchain,   // resized or out of date: rebuild, then draw
  Draw,
};

FrameAction decideFrameAction(VkExtent2D framebuffer, VkExtent2D swapchain, bool swapchainStale);

}  // namespace eng::vk
