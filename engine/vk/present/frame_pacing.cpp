#include "engine/vk/present/frame_pacing.h"

#include <algorithm>
#include <cmath>

namespace eng::vk {

FrameAction decideFrameAction(VkExtent2D framebuffer, VkExtent2D swapchain, bool swapchainStale) {
  if (framebuffer.width == 0 || framebuffer.height == 0) return FrameAction::Skip;
  if (swapchainStale || framebuffer.width != swapchain.width || framebuffer.height != swapchain.height)
    return FrameAction::RecreateSwapchain;
  return FrameAction::Draw;
}

AdaptiveRenderScale::AdaptiveRenderScale(float initial, const Limits& limits)
    : limits_(limits), scale_(snap(initial)) {}

float AdaptiveRenderScale::snap(float scale) const {
  const float snapped = std::round(scale / limits_.step) * limits_.step;
  return std::clamp(snapped, limits_.minScale, limits_.maxScale);
}

bool AdaptiveRenderScale::addFrame(double seconds) {
  if (!(seconds > 0.0)) return false;
  frames_[count_++] = seconds;
  if (count_ < kWindow) return false;
  count_ = 0;
  std::nth_element(frames_.begin(), frames_.begin() + kWindow / 2, frames_.end());
  const double median = frames_[kWindow / 2];
  float next = scale_;
  if (median > limits_.targetSeconds * 1.08) {
    // Pixels scale with the square; the fixed part of a frame makes this an
    // underestimate, which the next window corrects.
    const float wanted = scale_ * float(std::sqrt(limits_.targetSeconds / median));
    next = std::min(std::floor(wanted / limits_.step + 1e-3f) * limits_.step, scale_ - limits_.step);
  } else if (median < limits_.targetSeconds * 0.7) {
    next = scale_ + limits_.step;
  }
  next = snap(next);
  if (std::abs(next - scale_) < 0.5f * limits_.step) return false;
  scale_ = next;
  return true;
}

}  // namespace eng::vk
