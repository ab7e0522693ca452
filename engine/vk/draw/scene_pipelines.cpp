#include "engine/vk/draw/scene_pipelines.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/vk/device/vk_result.h"
#include "engine/vk/draw/pipeline_shape.h"

namespace eng::vk {
namespace {

Result<UniquePipeline> createMorphPipeline(const Context& ctx, const SceneLayouts& layouts, VkShaderModule module) {
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = shaderStage(VK_SHADER_STAGE_COMPUTE_BIT, module);
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
  background.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, bgVert->get()),
                       shaderStage(VK_SHADER_STAGE_FRAGMENT_BIT, bgFrag->get())};
  background.meshVertices = false;
  background.cull = VK_CULL_MODE_NONE;
  background.depth = false;
  auto bg = createGraphicsPipeline(ctx, layouts.pipelineLayout(), renderPass, samples, background);
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
    capture.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, captureVert->get())};
    capture.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;  // every vertex exactly once per instance
    capture.cull = VK_CULL_MODE_NONE;
    capture.depth = false;
    capture.rasterizerDiscard = true;
    auto cap = createGraphicsPipeline(ctx, layouts.pipelineLayout(), renderPass, samples, capture);
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
  mesh.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, meshVert->get()),
                 shaderStage(VK_SHADER_STAGE_FRAGMENT_BIT, meshFrag->get())};
  mesh.stages[0].pSpecializationInfo = &vertexInfo;
  mesh.stages[1].pSpecializationInfo = &constantsInfo;
  for (size_t sides = 0; sides < kMeshSides; ++sides)
    for (size_t alpha = 0; alpha < kAlphaPipelines; ++alpha) {
      mesh.cull = sides == kDoubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
      mesh.frontFace = sides == kCulledClockwise ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
      mesh.blend = alpha == size_t(AlphaPipeline::Blend);
      constants.alphaMask = alpha == size_t(AlphaPipeline::Mask) ? VK_TRUE : VK_FALSE;
      auto pipeline = createGraphicsPipeline(ctx, layouts.pipelineLayout(), renderPass, samples, mesh);
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
      auto pipeline = createGraphicsPipeline(ctx, layouts.pipelineLayout(), renderPass, samples, mesh);
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
  shadow.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, shadowVert->get())};
  shadow.cull = VK_CULL_MODE_NONE;  // double-sided and open meshes cast shadows too
  shadow.colorOutput = false;
  shadow.depthBias = true;
  auto shadowPipeline = createGraphicsPipeline(ctx, layouts.pipelineLayout(), shadowPass, VK_SAMPLE_COUNT_1_BIT, shadow);
  if (!shadowPipeline) return shadowPipeline.error();
  shadow_ = std::move(shadowPipeline).value();
  auto shadowMaskVert = createShaderModule(ctx, shaders, "shadow_mask_vert");
  if (!shadowMaskVert) return shadowMaskVert.error();
  auto shadowMaskFrag = createShaderModule(ctx, shaders, "shadow_mask_frag");
  if (!shadowMaskFrag) return shadowMaskFrag.error();
  shadow.stages = {shaderStage(VK_SHADER_STAGE_VERTEX_BIT, shadowMaskVert->get()),
                   shaderStage(VK_SHADER_STAGE_FRAGMENT_BIT, shadowMaskFrag->get())};
  auto shadowMasked = createGraphicsPipeline(ctx, layouts.pipelineLayout(), shadowPass, VK_SAMPLE_COUNT_1_BIT, shadow);
  if (!shadowMasked) return shadowMasked.error();
  shadowMasked_ = std::move(shadowMasked).value();
  return {};
}

}  // namespace eng::vk
