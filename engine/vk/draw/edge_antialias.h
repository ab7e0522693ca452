#pragma once
// Edge-aware anti-aliasing of a 1-sample image (engine/shaders/edge_antialias.frag,
// FXAA 3.11-style): one full-screen pass that reads the rendered image and
// writes a second one of the same format. On a CPU rasteriser it costs a
// fraction of 4x multisampling (the 1x image is shaded once per pixel and the
// pass touches each pixel once more), and softens the stair-steps that make
// a 1x picture read differently (silhouettes, lip line, teeth).
//
//   EdgeAntialiasPipeline   the shared part: render pass, layouts, sampler, pipeline
//   EdgeAntialiasTarget     one image's part: output image, framebuffer, descriptor set
#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/shader_library.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class EdgeAntialiasPipeline {
 public:
  // `color`: the format of both images (the filter blends what the sampler
  // returns, linear colour for an sRGB format).
  static Result<EdgeAntialiasPipeline> create(const Context& ctx, const ShaderLibrary& shaders, VkFormat color);

  VkFormat format() const { return format_; }
  VkRenderPass renderPass() const { return renderPass_.get(); }
  VkDescriptorSetLayout setLayout() const { return setLayout_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkPipeline pipeline() const { return pipeline_.get(); }
  VkSampler sampler() const { return sampler_.get(); }

 private:
  Result<void> createPipeline(const Context& ctx, const ShaderLibrary& shaders);

  VkFormat format_ = VK_FORMAT_UNDEFINED;
  UniqueRenderPass renderPass_;
  UniqueDescriptorSetLayout setLayout_;
  UniquePipelineLayout layout_;
  UniqueSampler sampler_;
  UniquePipeline pipeline_;
};

class EdgeAntialiasTarget {
 public:
  // `source`: the rendered image (sampled usage) of `extent`; `pipeline` must
  // outlive the target.
  static Result<EdgeAntialiasTarget> create(const Context& ctx, const EdgeAntialiasPipeline& pipeline,
                                            const GpuImage& source, VkExtent2D extent);

  // After the pass that rendered the source and left it in
  // TRANSFER_SRC_OPTIMAL with its writes ordered before transfers (the scene
  // pass): makes it readable, filters it into output(), which ends in
  // TRANSFER_SRC_OPTIMAL, ready to be copied; the source is left in
  // SHADER_READ_ONLY_OPTIMAL (the next scene pass starts from UNDEFINED).
  void record(VkCommandBuffer cmd) const;
  const GpuImage& output() const { return output_; }

 private:
  const EdgeAntialiasPipeline* pipeline_ = nullptr;
  VkImage source_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  GpuImage output_;
  UniqueFramebuffer framebuffer_;
  UniqueDescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;  // from pool_
};

}  // namespace eng::vk
