#include "engine/vk/device/render_pass.h"

#include <array>
#include <span>
#include <vector>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<VkFormat> chooseDepthFormat(const Context& ctx) {
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT,
                     VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  return makeError(ErrorKind::Device, "no depth attachment format supported by " + ctx.deviceInfo().name,
                   VK_ERROR_FORMAT_NOT_SUPPORTED);
}

VkAttachmentDescription attachmentDescription(VkFormat format, VkSampleCountFlagBits samples, VkAttachmentLoadOp load,
                                              VkAttachmentStoreOp store, VkImageLayout initialLayout,
                                              VkImageLayout finalLayout) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = samples;
  a.loadOp = load;
  a.storeOp = store;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = initialLayout;
  a.finalLayout = finalLayout;
  return a;
}

VkSampleCountFlagBits usableSampleCount(const Context& ctx, VkSampleCountFlagBits requested) {
  VkSampleCountFlagBits best = VK_SAMPLE_COUNT_1_BIT;
  const VkPhysicalDeviceLimits& limits = ctx.deviceInfo().properties.limits;
  const VkSampleCountFlags supported = limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
  for (uint32_t bit = VK_SAMPLE_COUNT_1_BIT; bit <= static_cast<uint32_t>(requested); bit <<= 1) {
    if (supported & bit) best = static_cast<VkSampleCountFlagBits>(bit);
  }
  return best;
}

Result<UniqueRenderPass> createOneSubpassPass(const Context& ctx, std::span<const VkAttachmentDescription> attachments,
                                              const VkSubpassDescription& subpass,
                                              std::span<const VkSubpassDependency> dependencies) {
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = static_cast<uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = static_cast<uint32_t>(dependencies.size());
  info.pDependencies = dependencies.data();
  VkRenderPass pass = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateRenderPass(ctx.device(), &info, nullptr, &pass));
  return UniqueRenderPass(ctx.device(), pass);
}


Result<UniqueRenderPass> createSceneRenderPass(const Context& ctx, const TargetFormat& format,
                                               VkImageLayout finalLayout) {
  const bool msaa = format.samples != VK_SAMPLE_COUNT_1_BIT;
  std::vector<VkAttachmentDescription> attachments;

  attachments.push_back(attachmentDescription(format.color, format.samples, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                              msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE,
                                              VK_IMAGE_LAYOUT_UNDEFINED,
                                              msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : finalLayout));
  attachments.push_back(attachmentDescription(format.depth, format.samples, VK_ATTACHMENT_LOAD_OP_CLEAR,
                                              VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
                                              VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL));
  if (msaa)
    attachments.push_back(attachmentDescription(format.color, VK_SAMPLE_COUNT_1_BIT, VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                                VK_ATTACHMENT_STORE_OP_STORE, VK_IMAGE_LAYOUT_UNDEFINED, finalLayout));

  const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolveRef{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pDepthStencilAttachment = &depthRef;
  subpass.pResolveAttachments = msaa ? &resolveRef : nullptr;

  constexpr VkPipelineStageFlags kAttachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  constexpr VkAccessFlags kAttachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const std::array dependencies{
      // Previous use of the attachments (last frame, a copy, the presentation engine
      // via the acquire semaphore's stage) before this pass writes them.
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, kAttachmentStages | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          kAttachmentStages, VK_ACCESS_TRANSFER_READ_BIT | kAttachmentWrites,
                          kAttachmentWrites | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT, 0},
      // The resolved image is copied (readback, screenshot) after the pass.
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, 0},
  };

  return createOneSubpassPass(ctx, attachments, subpass, dependencies);
}

Result<UniqueRenderPass> createColorPass(const Context& ctx, VkFormat color, VkAttachmentLoadOp load,
                                         VkImageLayout finalLayout) {
  const VkImageLayout initialLayout =
      load == VK_ATTACHMENT_LOAD_OP_LOAD ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
  const VkAttachmentDescription attachment = attachmentDescription(color, VK_SAMPLE_COUNT_1_BIT, load,
                                                                   VK_ATTACHMENT_STORE_OP_STORE, initialLayout, finalLayout);
  const VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  constexpr VkAccessFlags kColorAccess = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  const std::array dependencies{
      // The blit that filled the image (or the last copy out of it), before the pass draws.
      VkSubpassDependency{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, kColorAccess, 0},
      // Read-backs and screenshots copy the image after the pass.
      VkSubpassDependency{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, 0},
  };
  return createOneSubpassPass(ctx, {&attachment, 1}, subpass, dependencies);
}

Result<UniqueRenderPass> createOverlayRenderPass(const Context& ctx, VkFormat color, VkImageLayout finalLayout) {
  return createColorPass(ctx, color, VK_ATTACHMENT_LOAD_OP_LOAD, finalLayout);
}

}  // namespace eng::vk
