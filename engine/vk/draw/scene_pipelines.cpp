#include "engine/vk/draw/scene_pipelines.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

VkPipelineShaderStageCreateInfo stage(VkShaderStageFlagBits flags, VkShaderModule module) {
  VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  s.stage = flags;
  s.module = module;
  s.pName = "main";
  return s;
}

// Describes one pipeline; fixed-function state differs only in these fields.
struct PipelineShape {
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  bool meshVertices = true;  // the four per-vertex attribute streams
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cull = VK_CULL_MODE_BACK_BIT;
  VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // glTF winding; the projection flips y, not the winding
  bool depth = true;
  bool rasterizerDiscard = false;
  bool colorOutput = true;   // false: depth-only pass (no colour attachment)
  bool depthBias = false;    // slope-scaled bias against shadow acne
  bool blend = false;        // alpha blending over what is drawn (tests depth, writes none)
};

// Long: one VkGraphicsPipelineCreateInfo filled state by state, in the order
// Vulkan lists them; split up, each piece would only move a struct around.
Result<UniquePipeline> createPipeline(const Context& ctx, const SceneLayouts& layouts, VkRenderPass renderPass,
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
  info.layout = layouts.pipelineLayout();
  info.renderPass = renderPass;
  info.subpass = 0;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(ctx.device(), pipeline);
}

Result<UniquePipeline> createMorphPipeline(const Context& ctx, const SceneLayouts& layouts, VkShaderModule module) {
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = stage(VK_SHADER_STAGE_COMPUTE_BIT, module);
  info.layout = layouts.morphPipelineLayout();
  VkPipeline pipeline = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(ctx.device(), pipeline);
}

}  // namespace

Result<ScenePipelines> ScenePipelines::create(const Context& ctx, const SceneLayouts& layouts,
                                              const ShaderLibrary& shaders, VkRenderPass renderPass,
                                              VkSampleCountFlagBits samples, VkRenderPass shadowPass,
                                              const QualitySettings& quality) {
  ScenePipelines p;
  if (auto made = p.createMeshPipelines(ctx, layouts, shaders, renderPass, samples, quality); !made) return made.error();
  auto bgVert = createShaderModule(ctx, shaders, "background_vert");
  if (!bgVert) return bgVert.error();
  auto bgFrag = createShaderModule(ctx, shaders, "background_frag");
  if (!bgFrag) return bgFrag.error();

  PipelineShape background;
  background.stages = {stage(VK_SHADER_STAGE_VERTEX_BIT, bgVert->get()),
                       stage(VK_SHADER_STAGE_FRAGMENT_BIT, bgFrag->get())};
  background.meshVertices = false;
  background.cull = VK_CULL_MODE_NONE;
  background.depth = false;
  auto bg = createPipeline(ctx, layouts, renderPass, samples, background);
  if (!bg) return bg.error();
  p.background_ = std::move(bg).value();

  if (auto made = p.createShadowPipelines(ctx, layouts, shaders, shadowPass); !made) return made.error();

  auto morphComp = createShaderModule(ctx, shaders, "morph_comp");
  if (!morphComp) return morphComp.error();
  auto morph = createMorphPipeline(ctx, layouts, morphComp->get());
  if (!morph) return morph.error();
  p.morph_ = std::move(morph).value();

  if (ctx.deviceInfo().vertexPipelineStores) {
    auto captureVert = createShaderModule(ctx, shaders, "capture_vert");
    if (!captureVert) return captureVert.error();
    PipelineShape capture;
    capture.stages = {stage(VK_SHADER_STAGE_VERTEX_BIT, captureVert->get())};
    capture.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;  // every vertex exactly once per instance
    capture.cull = VK_CULL_MODE_NONE;
    capture.depth = false;
    capture.rasterizerDiscard = true;
    auto cap = createPipeline(ctx, layouts, renderPass, samples, capture);
    if (!cap) return cap.error();
    p.capture_ = std::move(cap).value();
  }
  return p;
}

// The mesh pipelines (by sidedness and alpha mode) and the MToon outlines,
// one vertex and fragment shader specialised per pipeline.
Result<void> ScenePipelines::createMeshPipelines(const Context& ctx, const SceneLayouts& layouts,
                                                 const ShaderLibrary& shaders, VkRenderPass renderPass,
                                                 VkSampleCountFlagBits samples, const QualitySettings& quality) {
  auto meshVert = createShaderModule(ctx, shaders, "mesh_vert");
  if (!meshVert) return meshVert.error();
  auto meshFrag = createShaderModule(ctx, shaders, "mesh_frag");
  if (!meshFrag) return meshFrag.error();
  // The tier's switches in lighting.glsl (constant_id 0 and 1), and whether
  // mesh.frag may discard (constant_id 2: only the MASK pipelines, since a
  // shader that can discard loses early depth testing for every draw).
  // constant_id 3 (both stages, frame.glsl): the MToon outline pipelines.
  struct FragmentConstants {
    int32_t shadowFilterRadius;
    VkBool32 secondarySpecular;
    VkBool32 alphaMask;
    VkBool32 outline;
  } constants{int32_t(quality.shadowFilterRadius), quality.secondarySpecular ? VK_TRUE : VK_FALSE, VK_FALSE, VK_FALSE};
  const std::array entries{
      VkSpecializationMapEntry{0, offsetof(FragmentConstants, shadowFilterRadius), sizeof(int32_t)},
      VkSpecializationMapEntry{1, offsetof(FragmentConstants, secondarySpecular), sizeof(VkBool32)},
      VkSpecializationMapEntry{2, offsetof(FragmentConstants, alphaMask), sizeof(VkBool32)},
      VkSpecializationMapEntry{3, offsetof(FragmentConstants, outline), sizeof(VkBool32)}};
  const VkSpecializationInfo constantsInfo{uint32_t(entries.size()), entries.data(), sizeof(constants), &constants};
  VkBool32 vertexOutline = VK_FALSE;
  const VkSpecializationMapEntry vertexEntry{3, 0, sizeof(VkBool32)};
  const VkSpecializationInfo vertexInfo{1, &vertexEntry, sizeof(VkBool32), &vertexOutline};
  PipelineShape mesh;
  mesh.stages = {stage(VK_SHADER_STAGE_VERTEX_BIT, meshVert->get()),
                 stage(VK_SHADER_STAGE_FRAGMENT_BIT, meshFrag->get())};
  mesh.stages[0].pSpecializationInfo = &vertexInfo;
  mesh.stages[1].pSpecializationInfo = &constantsInfo;
  for (size_t sides = 0; sides < kMeshSides; ++sides)
    for (size_t alpha = 0; alpha < kAlphaPipelines; ++alpha) {
      mesh.cull = sides == kDoubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
      mesh.frontFace = sides == kCulledClockwise ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
      mesh.blend = alpha == size_t(AlphaPipeline::Blend);
      constants.alphaMask = alpha == size_t(AlphaPipeline::Mask) ? VK_TRUE : VK_FALSE;
      auto pipeline = createPipeline(ctx, layouts, renderPass, samples, mesh);
      if (!pipeline) return pipeline.error();
      mesh_[sides][alpha] = std::move(pipeline).value();
    }
  // Outlines: the hull's back faces (front faces culled), opaque or cut out.
  vertexOutline = VK_TRUE;
  constants.outline = VK_TRUE;
  mesh.blend = false;
  mesh.cull = VK_CULL_MODE_FRONT_BIT;
  for (size_t winding = 0; winding < 2; ++winding)
    for (size_t masked = 0; masked < 2; ++masked) {
      mesh.frontFace = winding == 1 ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
      constants.alphaMask = masked == 1 ? VK_TRUE : VK_FALSE;
      auto pipeline = createPipeline(ctx, layouts, renderPass, samples, mesh);
      if (!pipeline) return pipeline.error();
      outline_[winding][masked] = std::move(pipeline).value();
    }
  return {};
}

// The shadow map's depth-only pipelines: opaque casters, and cut-out ones
// whose fragment shader discards where the base colour's alpha is below its cutoff.
Result<void> ScenePipelines::createShadowPipelines(const Context& ctx, const SceneLayouts& layouts,
                                                   const ShaderLibrary& shaders, VkRenderPass shadowPass) {
  auto shadowVert = createShaderModule(ctx, shaders, "shadow_vert");
  if (!shadowVert) return shadowVert.error();
  PipelineShape shadow;
  shadow.stages = {stage(VK_SHADER_STAGE_VERTEX_BIT, shadowVert->get())};
  shadow.cull = VK_CULL_MODE_NONE;  // double-sided and open meshes cast shadows too
  shadow.colorOutput = false;
  shadow.depthBias = true;
  auto shadowPipeline = createPipeline(ctx, layouts, shadowPass, VK_SAMPLE_COUNT_1_BIT, shadow);
  if (!shadowPipeline) return shadowPipeline.error();
  shadow_ = std::move(shadowPipeline).value();
  auto shadowMaskVert = createShaderModule(ctx, shaders, "shadow_mask_vert");
  if (!shadowMaskVert) return shadowMaskVert.error();
  auto shadowMaskFrag = createShaderModule(ctx, shaders, "shadow_mask_frag");
  if (!shadowMaskFrag) return shadowMaskFrag.error();
  shadow.stages = {stage(VK_SHADER_STAGE_VERTEX_BIT, shadowMaskVert->get()),
                   stage(VK_SHADER_STAGE_FRAGMENT_BIT, shadowMaskFrag->get())};
  auto shadowMasked = createPipeline(ctx, layouts, shadowPass, VK_SAMPLE_COUNT_1_BIT, shadow);
  if (!shadowMasked) return shadowMasked.error();
  shadowMasked_ = std::move(shadowMasked).value();
  return {};
}

}  // namespace eng::vk
