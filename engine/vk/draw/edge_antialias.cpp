#include "engine/vk/draw/edge_antialias.h"

#include <array>

#include "engine/vk/device/descriptor_write.h"
#include "engine/vk/device/render_pass.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

// The filtered image: every pixel written (nothing loaded), copied after the pass.
Result<UniqueRenderPass> createFilterPass(const Context& ctx, VkFormat color) {
  const VkAttachmentDescription attachment =
      attachmentDescription(color, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE,
                            VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  const std::array dependencies{
      // The previous frame's copy out of the image, before this pass writes it.
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
      // The read-back copy after the pass.
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, 0},
  };
  return createOneSubpassPass(ctx, {&attachment, 1}, subpass, dependencies);
}

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
  p.renderPass_ = ENG_TRY_VALUE(createFilterPass(ctx, color));
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
// depth or blending; viewport and scissor set per target.
Result<void> EdgeAntialiasPipeline::createPipeline(const Context& ctx, const ShaderLibrary& shaders) {
  const UniqueShaderModule vert = ENG_TRY_VALUE(createShaderModule(ctx, shaders, "background_vert"));
  const UniqueShaderModule frag = ENG_TRY_VALUE(createShaderModule(ctx, shaders, "edge_antialias_frag"));
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  for (VkPipelineShaderStageCreateInfo& s : stages) s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert.get();
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag.get();
  stages[1].pName = "main";

  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo inputAssembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  inputAssembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  const std::array dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blendAttachment;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &inputAssembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout_.get();
  info.renderPass = renderPass_.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  pipeline_ = UniquePipeline(ctx.device(), pipeline);
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
