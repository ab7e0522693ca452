#include "engine/vk/draw/shadow_map.h"

#include <array>

#include "engine/vk/device/render_pass.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<ShadowMap> ShadowMap::create(const Context& ctx, uint32_t size) {
  // A depth format that can be rendered and sampled; linear filtering gives 2x2 PCF per tap for free.
  VkFormat format = VK_FORMAT_UNDEFINED;
  bool linear = false;
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), f, &props);
    constexpr VkFormatFeatureFlags kNeeded =
        VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if ((props.optimalTilingFeatures & kNeeded) == kNeeded) {
      format = f;
      linear = props.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
      break;
    }
  }
  if (format == VK_FORMAT_UNDEFINED)
    return makeError(ErrorKind::Device, "shadow map: no depth format that " + ctx.deviceInfo().name + " can both render and sample",
                     VK_ERROR_FORMAT_NOT_SUPPORTED);

  ShadowMap s;
  s.size_ = size;
  const VkAttachmentDescription depth =
      attachmentDescription(format, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
                            VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
  const VkAttachmentReference depthRef{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depthRef;
  constexpr VkPipelineStageFlags kDepthStages =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const std::array dependencies{
      // The previous frame's scene pass read the map: finish before overwriting it.
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, kDepthStages, 0,
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                          0},
      // This frame's scene pass samples it.
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, kDepthStages, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, 0},
  };
  auto pass = createOneSubpassPass(ctx, std::span(&depth, 1), subpass, dependencies);
  if (!pass) return pass.error().prefixed("shadow map: ");
  s.renderPass_ = std::move(pass).value();

  ImageDesc desc;
  desc.extent = {size, size};
  desc.format = format;
  desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  desc.debugName = "key light shadow map";
  auto image = GpuImage::create(ctx, desc);
  if (!image) return image.error();
  s.image_ = std::move(image).value();

  const VkImageView view = s.image_.view();
  VkFramebufferCreateInfo fbInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fbInfo.renderPass = s.renderPass_.get();
  fbInfo.attachmentCount = 1;
  fbInfo.pAttachments = &view;
  fbInfo.width = size;
  fbInfo.height = size;
  fbInfo.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFramebuffer(ctx.device(), &fbInfo, nullptr, &fb));
  s.framebuffer_ = UniqueFramebuffer(ctx.device(), fb);

  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  samplerInfo.minFilter = samplerInfo.magFilter;
  samplerInfo.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  samplerInfo.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  samplerInfo.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  samplerInfo.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // outside the map: lit
  samplerInfo.compareEnable = VK_TRUE;
  samplerInfo.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  VkSampler sampler = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateSampler(ctx.device(), &samplerInfo, nullptr, &sampler));
  s.sampler_ = UniqueSampler(ctx.device(), sampler);
  return s;
}

void ShadowMap::begin(VkCommandBuffer cmd) const {
  VkClearValue clear{};
  clear.depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass_.get();
  begin.framebuffer = framebuffer_.get();
  begin.renderArea = {{0, 0}, {size_, size_}};
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.0f, 0.0f, float(size_), float(size_), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {size_, size_}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void ShadowMap::end(VkCommandBuffer cmd) const { vkCmdEndRenderPass(cmd); }

}  // namespace eng::vk
