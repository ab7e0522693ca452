#pragma once
// What the window loop does with the next frame, from the window's current
// framebuffer size and the swapchain's state. Pure, so resize and minimise
// handling is testable without a window system.
#include <array>
#include <cstdint>

#include <vulkan/vulkan.h>

namespace eng::vk {

enum class FrameAction {
  Skip,                // minimised (0x0): nothing to draw into; wait for events
  RecreateSwapchain,   // resized or out of date: rebuild, then draw
  Draw,
};

FrameAction decideFrameAction(VkExtent2D framebuffer, VkExtent2D swapchain, bool swapchainStale);

// Dynamic resolution for a CPU rasteriser, whose frame cost is mostly per
// pixel: the 3D view's render scale follows the measured time between
// presented frames. Over each window of frames the median decides (a
// screenshot's read-back or a stalled present does not): slower than the
// target lowers the scale as far as the pixel count predicts (at least one
// step); well under it raises it one step. Scales are multiples of `step`
// within [minScale, maxScale], so few distinct sizes are ever built.
class AdaptiveRenderScale {
 public:
  struct Limits {
    float minScale = 0.45f;  // below this the face turns visibly soft when blitted up
    float maxScale = 0.9f;   // stays below 1: the view is always blitted (its passes are fixed at creation)
    float step = 0.05f;
    double targetSeconds = 1.0 / 32.0;  // aims a little above 30 frames/s
  };
  static constexpr uint32_t kWindow = 8;

  AdaptiveRenderScale(float initial, const Limits& limits);
  float scale() const { return scale_; }
  // One presented frame's wall time. True when scale() changed (the caller
  // rebuilds the view's images and calls restart()).
  bool addFrame(double seconds);
  // Drops the frames gathered so far (after a rebuild, a skipped frame).
  void restart() { count_ = 0; }

 private:
  float snap(float scale) const;
  Limits limits_;
  float scale_;
  std::array<double, kWindow> frames_{};
  uint32_t count_ = 0;
};

}  // namespace eng::vk
