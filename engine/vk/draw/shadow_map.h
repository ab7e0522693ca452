#pragma once
// The key light's shadow map: a depth-only render pass into a square depth
// image that the scene pass then samples with a comparison sampler (PCF).
// One map serves every frame slot: the pass's dependencies order its writes
// after earlier frames' reads on the same queue.
#include <cstdint>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class ShadowMap {
 public:
  static Result<ShadowMap> create(const Context& ctx, uint32_t size = 1024);

  VkRenderPass renderPass() const { return renderPass_.get(); }
  VkImageView view() const { return image_.view(); }
  VkSampler sampler() const { return sampler_.get(); }
  uint32_t size() const { return size_; }

  // Begins the pass (depth cleared to far) with viewport and scissor set.
  void begin(VkCommandBuffer cmd) const;
  void end(VkCommandBuffer cmd) const;

 private:
  uint32_t size_ = 0;
  UniqueRenderPass renderPass_;
  GpuImage image_;
  UniqueFramebuffer framebuffer_;
  UniqueSampler sampler_;
};

}  // namespace eng::vk
