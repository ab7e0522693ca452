#pragma once
// The one render-pass shape every target uses: multisampled colour + depth,
// resolved into a single-sample image (an offscreen image or a swapchain
// image). With 1 sample the colour attachment is that image directly.
#include <span>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

struct TargetFormat {
  VkFormat color = VK_FORMAT_R8G8B8A8_SRGB;
  VkFormat depth = VK_FORMAT_D32_SFLOAT;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;
};

// The first depth format the device can render to (D32, D32S8, D24S8, D16).
Result<VkFormat> chooseDepthFormat(const Context& ctx);

// One attachment of a render pass without a stencil aspect (stencil ops are
// DONT_CARE): the few fields that differ between passes, in one line.
// A render pass of one subpass over `attachments`.
Result<UniqueRenderPass> createOneSubpassPass(const Context& ctx, std::span<const VkAttachmentDescription> attachments,
                                              const VkSubpassDescription& subpass,
                                              std::span<const VkSubpassDependency> dependencies);

VkAttachmentDescription attachmentDescription(VkFormat format, VkSampleCountFlagBits samples, VkAttachmentLoadOp load,
                                              VkAttachmentStoreOp store, VkImageLayout initialLayout,
                                              VkImageLayout finalLayout);

// `requested` clamped to what the device supports for colour and depth together.
VkSampleCountFlagBits usableSampleCount(const Context& ctx, VkSampleCountFlagBits requested);

// Clears colour and depth; the resolved image ends in `finalLayout` and may be
// copied from right after the pass (the pass orders its writes before transfers).
Result<UniqueRenderPass> createSceneRenderPass(const Context& ctx, const TargetFormat& format,
                                               VkImageLayout finalLayout);

// One single-sample colour attachment, no depth, ending in `finalLayout` and
// copyable right after the pass. load LOAD: drawn over what a transfer left
// in it (starts in TRANSFER_DST_OPTIMAL); DONT_CARE: every pixel is drawn
// (starts UNDEFINED, after any earlier copy out of it).
Result<UniqueRenderPass> createColorPass(const Context& ctx, VkFormat color, VkAttachmentLoadOp load,
                                         VkImageLayout finalLayout);

// One single-sample colour attachment drawn over what a transfer (a blit of
// the 3D view) left in it: starts in TRANSFER_DST_OPTIMAL, loads, ends in
// `finalLayout`, and may be copied from right after the pass.
Result<UniqueRenderPass> createOverlayRenderPass(const Context& ctx, VkFormat color, VkImageLayout finalLayout);

}  // namespace eng::vk
