#pragma once
// Graphics pipelines described by the few fields that differ between them
// (PipelineShape), built with everything else fixed: dynamic viewport and
// scissor, no stencil, one colour attachment or none. The scene's pipelines
// and the edge-aware anti-aliasing pass share it.
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

// A stage running `module`'s "main".
VkPipelineShaderStageCreateInfo shaderStage(VkShaderStageFlagBits flags, VkShaderModule module);

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

// With `layout` for `renderPass` (subpass 0) at `samples`.
Result<UniquePipeline> createGraphicsPipeline(const Context& ctx, VkPipelineLayout layout, VkRenderPass renderPass,
                                              VkSampleCountFlagBits samples, const PipelineShape& shape);

}  // namespace eng::vk
