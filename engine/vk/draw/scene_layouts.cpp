#include "engine/vk/draw/scene_layouts.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/vk/draw/gpu_types.h"
#include "engine/vk/draw/texture.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

Result<UniqueDescriptorSetLayout> createSetLayout(const Context& ctx,
                                                  std::span<const VkDescriptorSetLayoutBinding> bindings) {
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = static_cast<uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &layout));
  return UniqueDescriptorSetLayout(ctx.device(), layout);
}

// Both sets and DrawConstants as push constants for `stages`.
Result<UniquePipelineLayout> createPipelineLayout(const Context& ctx, std::span<const VkDescriptorSetLayout> sets,
                                                  VkShaderStageFlags stages) {
  const VkPushConstantRange push{stages, 0, sizeof(DrawConstants)};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = static_cast<uint32_t>(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = 1;
  info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout));
  return UniquePipelineLayout(ctx.device(), layout);
}

VkDescriptorSetLayoutBinding binding(uint32_t index, VkDescriptorType type, VkShaderStageFlags stages) {
  return {index, type, 1, stages, nullptr};
}

}  // namespace

Result<SceneLayouts> SceneLayouts::create(const Context& ctx) {
  SceneLayouts s;
  constexpr VkShaderStageFlags kVs = VK_SHADER_STAGE_VERTEX_BIT;
  constexpr VkShaderStageFlags kFs = VK_SHADER_STAGE_FRAGMENT_BIT;
  constexpr VkShaderStageFlags kBoth = kVs | kFs;
  constexpr VkShaderStageFlags kCs = VK_SHADER_STAGE_COMPUTE_BIT;

  const std::array frameBindings{
      binding(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kBoth),
      binding(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBoth | kCs),
      binding(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBoth),
      binding(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kVs),
      binding(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kVs),
      binding(6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBoth),
      binding(7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kVs | kCs),
      binding(8, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kCs | kFs),
  };
  auto frameSet = createSetLayout(ctx, frameBindings);
  if (!frameSet) return frameSet.error();
  s.frameSet_ = std::move(frameSet).value();

  const std::array primitiveBindings{
      binding(0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kCs),
      binding(1, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kCs),
      binding(2, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kCs),
      binding(3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kFs),
      binding(6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kVs),
      binding(7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(9, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(12, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(13, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFs),
      binding(14, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kVs),
  };
  auto primitiveSet = createSetLayout(ctx, primitiveBindings);
  if (!primitiveSet) return primitiveSet.error();
  s.primitiveSet_ = std::move(primitiveSet).value();

  const std::array setLayouts{s.frameSet_.get(), s.primitiveSet_.get()};
  auto pipelineLayout = createPipelineLayout(ctx, setLayouts, kBoth);
  if (!pipelineLayout) return pipelineLayout.error();
  s.pipelineLayout_ = std::move(pipelineLayout).value();
  auto morphLayout = createPipelineLayout(ctx, setLayouts, kCs);
  if (!morphLayout) return morphLayout.error();
  s.morphPipelineLayout_ = std::move(morphLayout).value();

  auto sampler = createSampler(ctx, TextureSampling{});
  if (!sampler) return sampler.error();
  s.sampler_ = std::move(sampler).value();

  const std::array<uint8_t, 4> whitePixel{255, 255, 255, 255};
  const std::array<std::span<const uint8_t>, 1> whiteLayers{whitePixel};
  auto white = createTexture(ctx, {1, 1, whiteLayers, VK_IMAGE_VIEW_TYPE_2D, "white texture"});
  if (!white) return white.error();
  s.white_ = std::move(white).value();

  const std::array<uint8_t, 4> clearPixel{0, 0, 0, 0};
  const std::array<std::span<const uint8_t>, 1> clearLayers{clearPixel};
  auto empty = createTexture(ctx, {1, 1, clearLayers, VK_IMAGE_VIEW_TYPE_2D_ARRAY, "empty detail array"});
  if (!empty) return empty.error();
  s.emptyDetail_ = std::move(empty).value();

  const std::vector<std::byte> zeros(256);
  auto placeholder = Buffer::createWithData(
      ctx, zeros, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "placeholder storage");
  if (!placeholder) return placeholder.error();
  s.placeholder_ = std::move(placeholder).value();
  for (auto [format, view] : {std::pair{VK_FORMAT_R32G32B32A32_SFLOAT, &s.placeholderVec4_},
                              std::pair{VK_FORMAT_R32_SFLOAT, &s.placeholderFloat_},
                              std::pair{VK_FORMAT_R32_UINT, &s.placeholderUint_}}) {
    auto texels = createTexelView(ctx, s.placeholder_.handle(), 0, zeros.size(), format);
    if (!texels) return texels.error();
    *view = std::move(texels).value();
  }
  return s;
}

}  // namespace eng::vk
