#include "engine/vk/draw/edge_antialias.h"

#include <array>

#include "engine/vk/device/descriptor_write.h"
#include "engine/vk/device/render_pass.h"
#include "engine/vk/device/vk_result.h"
#include "engine/vk/draw/pipeline_shape.h"

namespace eng::vk {
namespace {

// Bilinear (the edge search and the final blend read between texels), clamped to the edge.
Result<UniqueSampler> createBilinearSampler(const Context& ctx) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
  return UniqueSampler(ctx.device(), sampler);
}

}  // namespace

Result<EdgeAntialiasPipeline> EdgeAntialiasPipeline::create(const Context& ctx, const ShaderLibrary& shaders,
                                                            VkFormat color) {
  EdgeAntialiasPipeline p;
  p.format_ = color;
  // Every pixel written (nothing loaded), copied after the pass.
  p.renderPass_ = ENG_TRY_VALUE(createColorPass(ctx, color, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
  p.sampler_ = ENG_TRY_VALUE(createBilinearSampler(ctx));

  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                             VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 1;
  setInfo.pBindings = &binding;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorSetLayout(ctx.device(), &setInfo, nullptr, &setLayout));
  p.setLayout_ = UniqueDescriptorSetLayout(ctx.device(), setLayout);

  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreatePipelineLayout(ctx.device(), &layoutInfo, nullptr, &layout));
  p.layout_ = UniquePipelineLayout(ctx.device(), layout);
  ENG_TRY(p.createPipeline(ctx, shaders));
  return p;
}

// A full-screen triangle (background.vert) and the filter; no vertex input,
// depth or blending.
Result<void> EdgeAntialiasPipeline::createPipeline(const Context& ctx, const ShaderLibrary& shaders) {
  const UniqueShaderModule vert = ENG_TRY_VALUE(createShaderModule(ctx, shaders, "background_vert"));
  const UniqueShaderModule frag = ENG_TRY_VALUE(createShaderModule(ctx, shaders, "edge_antialias_frag"));
  PipelineShape shape;
  shape.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, vert.get()),
                  shaderStage(VK_SHADER_STAGE_FRAGMENT_BIT, frag.get())};
  shape.meshVertices = false;
  shape.cull = VK_CULL_MODE_NONE;
  shape.depth = false;
  pipeline_ = ENG_TRY_VALUE(createGraphicsPipeline(ctx, layout_.get(), renderPass_.get(), VK_SAMPLE_COUNT_1_BIT, shape));
  return {};
}

Result<EdgeAntialiasTarget> EdgeAntialiasTarget::create(const Context& ctx, const EdgeAntialiasPipeline& pipeline,
                                                        const GpuImage& source, VkExtent2D extent) {
  EdgeAntialiasTarget t;
  t.pipeline_ = &pipeline;
  t.source_ = source.handle();
  t.extent_ = extent;
  ImageDesc output;
  output.extent = extent;
  output.format = pipeline.format();
  output.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  output.debugName = "offscreen anti-aliased colour";
  t.output_ = ENG_TRY_VALUE(GpuImage::create(ctx, output));

  const VkImageView view = t.output_.view();
  VkFramebufferCreateInfo fbInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fbInfo.renderPass = pipeline.renderPass();
  fbInfo.attachmentCount = 1;
  fbInfo.pAttachments = &view;
  fbInfo.width = extent.width;
  fbInfo.height = extent.height;
  fbInfo.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFramebuffer(ctx.device(), &fbInfo, nullptr, &fb));
  t.framebuffer_ = UniqueFramebuffer(ctx.device(), fb);

  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  t.pool_ = UniqueDescriptorPool(ctx.device(), pool);
  const VkDescriptorSetLayout setLayout = pipeline.setLayout();
  VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocInfo.descriptorPool = pool;
  allocInfo.descriptorSetCount = 1;
  allocInfo.pSetLayouts = &setLayout;
  ENG_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &allocInfo, &t.set_));
  const VkDescriptorImageInfo image{pipeline.sampler(), source.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkWriteDescriptorSet write = imageWrite(t.set_, 0, &image);
  vkUpdateDescriptorSets(ctx.device(), 1, &write, 0, nullptr);
  return t;
}

void EdgeAntialiasTarget::record(VkCommandBuffer cmd) const {
  // The scene pass made its writes available to transfers; chain on from
  // there into the fragment shader's reads.
  recordImageBarrier(cmd, {.image = source_,
                           .oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           .newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                           .srcStage = VK_PIPELINE_STAGE_TRANSFER_BIT,
                           .dstStage = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                           .dstAccess = VK_ACCESS_SHADER_READ_BIT});
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pipeline_->renderPass();
  begin.framebuffer = framebuffer_.get();
  begin.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->pipeline());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->layout(), 0, 1, &set_, 0, nullptr);
  const VkViewport viewport{0.0f, 0.0f, float(extent_.width), float(extent_.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent_};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRenderPass(cmd);
}

}  // namespace eng::vk
