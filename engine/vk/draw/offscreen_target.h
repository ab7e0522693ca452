#pragma once
// Headless render target: MSAA colour (sRGB) + depth, resolved into a
// single-sample image that is copied to a host-visible buffer and read back
// as RGBA8 (sRGB-encoded, ready for PNG). A 1-sample target may filter its
// image with the edge-aware anti-aliasing pass (edge_antialias.h) before the copy.
#include <cstdint>
#include <functional>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/render_pass.h"
#include "engine/vk/device/unique_handle.h"
#include "engine/vk/draw/edge_antialias.h"

namespace eng::vk {

class OffscreenTarget {
 public:
  // samples is clamped to what the device supports (4 on every desktop GPU and lavapipe).
  // antialias (outliving the target): filters the image when the target has
  // one sample (a multisampled one is resolved as before); its format must be
  // the target's colour format (sRGB RGBA8).
  static Result<OffscreenTarget> create(const Context& ctx, uint32_t width, uint32_t height,
                                        VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT,
                                        const EdgeAntialiasPipeline* antialias = nullptr);

  VkRenderPass renderPass() const { return renderPass_.get(); }
  const TargetFormat& format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  bool edgeAntialiased() const { return static_cast<bool>(antialias_.output()); }

  // What one submission records around the target's render pass.
  struct Recorders {
    std::function<void(VkCommandBuffer)> beforePass;  // e.g. the shadow pass
    std::function<void(VkCommandBuffer)> inPass;      // the scene
    std::function<void(VkCommandBuffer)> afterPass;   // after the readback copy, e.g. a host-read barrier
    bool readback = true;  // false: no copy to the readback buffer (benchmarks time the frame alone)
  };
  // One submission: beforePass, the pass (cleared) with inPass, the
  // anti-aliasing pass where the target has one, a copy of the final image
  // to the readback buffer (unless !readback), afterPass;
  // waits for completion.
  // clearColor: linear RGBA the colour attachment starts from.
  Result<void> render(const Recorders& recorders, const glm::vec4& clearColor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // The same commands into `cmd`, for a caller that submits and waits itself
  // (frames in flight, OffscreenRenderer::submit).
  void record(VkCommandBuffer cmd, const Recorders& recorders, const glm::vec4& clearColor) const;
  // The last rendered image, RGBA8, top row first.
  eng::Image readPixels() const;

 private:
  const Context* ctx_ = nullptr;
  TargetFormat format_;
  VkExtent2D extent_{0, 0};
  UniqueRenderPass renderPass_;
  GpuImage msaaColor_;
  GpuImage depth_;
  GpuImage resolved_;
  EdgeAntialiasTarget antialias_;  // empty unless the image is filtered before the copy
  UniqueFramebuffer framebuffer_;
  Buffer readback_;
};

}  // namespace eng::vk
