#include "engine/vk/draw/pipeline_shape.h"

#include <array>

#include <glm/glm.hpp>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

VkPipelineShaderStageCreateInfo shaderStage(VkShaderStageFlagBits flags, VkShaderModule module) {
  VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  s.stage = flags;
  s.module = module;
  s.pName = "main";
  return s;
}

// Long: one VkGraphicsPipelineCreateInfo filled state by state, in the order
// Vulkan lists them; split up, each piece would only move a struct around.
Result<UniquePipeline> createGraphicsPipeline(const Context& ctx, VkPipelineLayout layout, VkRenderPass renderPass,
                                              VkSampleCountFlagBits samples, const PipelineShape& shape) {
  // Separate streams (binding = location): position, normal, texcoord, tangent, colour.
  const std::array bindings{
      VkVertexInputBindingDescription{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{1, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{2, sizeof(glm::vec2), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{3, sizeof(glm::vec4), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{4, sizeof(glm::vec4), VK_VERTEX_INPUT_RATE_VERTEX},
  };
  const std::array attributes{
      VkVertexInputAttributeDescription{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
      VkVertexInputAttributeDescription{1, 1, VK_FORMAT_R32G32B32_SFLOAT, 0},
      VkVertexInputAttributeDescription{2, 2, VK_FORMAT_R32G32_SFLOAT, 0},
      VkVertexInputAttributeDescription{3, 3, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
      VkVertexInputAttributeDescription{4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
  };
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (shape.meshVertices) {
    vertexInput.vertexBindingDescriptionCount = static_cast<uint32_t>(bindings.size());
    vertexInput.pVertexBindingDescriptions = bindings.data();
    vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
    vertexInput.pVertexAttributeDescriptions = attributes.data();
  }
  VkPipelineInputAssemblyStateCreateInfo inputAssembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  inputAssembly.topology = shape.topology;

  // Viewport and scissor are dynamic (targets resize); the capture pipeline
  // rasterises nothing, so it gets a fixed 1x1 viewport and no dynamic state.
  const VkViewport unitViewport{0, 0, 1, 1, 0, 1};
  const VkRect2D unitScissor{{0, 0}, {1, 1}};
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  if (shape.rasterizerDiscard) {
    viewport.pViewports = &unitViewport;
    viewport.pScissors = &unitScissor;
  }
  const std::array dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  if (!shape.rasterizerDiscard) {
    dynamic.dynamicStateCount = static_cast<uint32_t>(dynamicStates.size());
    dynamic.pDynamicStates = dynamicStates.data();
  }

  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.rasterizerDiscardEnable = shape.rasterizerDiscard ? VK_TRUE : VK_FALSE;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = shape.cull;
  raster.frontFace = shape.frontFace;
  raster.lineWidth = 1.0f;
  if (shape.depthBias) {
    raster.depthBiasEnable = VK_TRUE;
    raster.depthBiasConstantFactor = 1.5f;
    raster.depthBiasSlopeFactor = 2.0f;
  }

  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = samples;

  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = shape.depth ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = shape.depth && !shape.blend ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;

  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (shape.blend) {
    // "over": colour by the source's alpha; the target's alpha (coverage, for
    // transparent backgrounds) accumulates the same way.
    blendAttachment.blendEnable = VK_TRUE;
    blendAttachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blendAttachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blendAttachment.colorBlendOp = VK_BLEND_OP_ADD;
    blendAttachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blendAttachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blendAttachment.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = shape.colorOutput ? 1 : 0;
  blend.pAttachments = &blendAttachment;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<uint32_t>(shape.stages.size());
  info.pStages = shape.stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &inputAssembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = renderPass;
  info.subpass = 0;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(ctx.device(), pipeline);
}

}  // namespace eng::vk
