#include "engine/vk/draw/offscreen_target.h"

#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<OffscreenTarget> OffscreenTarget::create(const Context& ctx, uint32_t width, uint32_t height,
                                                VkSampleCountFlagBits samples,
                                                const EdgeAntialiasPipeline* antialias) {
  const VkPhysicalDeviceLimits& limits = ctx.deviceInfo().properties.limits;
  if (width == 0 || height == 0 || width > limits.maxFramebufferWidth || height > limits.maxFramebufferHeight)
    return makeError(ErrorKind::InvalidArgument, "offscreen target: size " + std::to_string(width) + "x" + std::to_string(height) +
                     " outside 1x1.." + std::to_string(limits.maxFramebufferWidth) + "x" +
                     std::to_string(limits.maxFramebufferHeight));
  OffscreenTarget t;
  t.ctx_ = &ctx;
  t.extent_ = {width, height};
  auto depthFormat = chooseDepthFormat(ctx);
  if (!depthFormat) return depthFormat.error();
  t.format_ = {VK_FORMAT_R8G8B8A8_SRGB, depthFormat.value(), usableSampleCount(ctx, samples)};
  const bool msaa = t.format_.samples != VK_SAMPLE_COUNT_1_BIT;
  const bool filtered = antialias != nullptr && !msaa;
  if (filtered && antialias->format() != t.format_.color)
    return makeError(ErrorKind::InvalidArgument, "offscreen target: anti-aliasing pass for format " +
                     std::to_string(antialias->format()) + ", target is " + std::to_string(t.format_.color));

  auto pass = createSceneRenderPass(ctx, t.format_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  if (!pass) return pass.error();
  t.renderPass_ = std::move(pass).value();

  ImageDesc resolved;
  resolved.extent = t.extent_;
  resolved.format = t.format_.color;
  resolved.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                   (filtered ? VK_IMAGE_USAGE_SAMPLED_BIT : 0);
  resolved.debugName = "offscreen resolved colour";
  auto resolvedImage = GpuImage::create(ctx, resolved);
  if (!resolvedImage) return resolvedImage.error();
  t.resolved_ = std::move(resolvedImage).value();
  if (filtered) t.antialias_ = ENG_TRY_VALUE(EdgeAntialiasTarget::create(ctx, *antialias, t.resolved_, t.extent_));

  if (msaa) {
    ImageDesc color = resolved;
    color.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
    color.samples = t.format_.samples;
    color.debugName = "offscreen msaa colour";
    auto colorImage = GpuImage::create(ctx, color);
    if (!colorImage) return colorImage.error();
    t.msaaColor_ = std::move(colorImage).value();
  }
  ImageDesc depth;
  depth.extent = t.extent_;
  depth.format = t.format_.depth;
  depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  depth.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  depth.samples = t.format_.samples;
  depth.debugName = "offscreen depth";
  auto depthImage = GpuImage::create(ctx, depth);
  if (!depthImage) return depthImage.error();
  t.depth_ = std::move(depthImage).value();

  std::vector<VkImageView> views;
  views.push_back(msaa ? t.msaaColor_.view() : t.resolved_.view());
  views.push_back(t.depth_.view());
  if (msaa) views.push_back(t.resolved_.view());
  VkFramebufferCreateInfo fbInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fbInfo.renderPass = t.renderPass_.get();
  fbInfo.attachmentCount = static_cast<uint32_t>(views.size());
  fbInfo.pAttachments = views.data();
  fbInfo.width = width;
  fbInfo.height = height;
  fbInfo.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFramebuffer(ctx.device(), &fbInfo, nullptr, &fb));
  t.framebuffer_ = UniqueFramebuffer(ctx.device(), fb);

  auto readback = Buffer::create(ctx, VkDeviceSize{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                 MemoryUsage::Readback, "offscreen readback");
  if (!readback) return readback.error();
  t.readback_ = std::move(readback).value();
  return t;
}

Result<void> OffscreenTarget::render(const Recorders& recorders, const glm::vec4& clearColor) {
  return ctx_->submitOneShot([&](VkCommandBuffer cmd) { record(cmd, recorders, clearColor); });
}

void OffscreenTarget::record(VkCommandBuffer cmd, const Recorders& recorders, const glm::vec4& clearColor) const {
  if (recorders.beforePass) recorders.beforePass(cmd);
  std::array<VkClearValue, 3> clears{};
  clears[0].color = {{clearColor.r, clearColor.g, clearColor.b, clearColor.a}};
  clears[1].depthStencil = {1.0f, 0};
  clears[2].color = clears[0].color;
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass_.get();
  begin.framebuffer = framebuffer_.get();
  begin.renderArea = {{0, 0}, extent_};
  begin.clearValueCount = format_.samples != VK_SAMPLE_COUNT_1_BIT ? 3 : 2;
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  if (recorders.inPass) recorders.inPass(cmd);
  vkCmdEndRenderPass(cmd);
  if (edgeAntialiased()) antialias_.record(cmd);
  if (!recorders.readback) {
    if (recorders.afterPass) recorders.afterPass(cmd);
    return;
  }

  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent_.width, extent_.height, 1};
  const VkImage copied = edgeAntialiased() ? antialias_.output().handle() : resolved_.handle();
  vkCmdCopyImageToBuffer(cmd, copied, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1,
                         &copy);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr,
                       0, nullptr);
  if (recorders.afterPass) recorders.afterPass(cmd);
}

eng::Image OffscreenTarget::readPixels() const {
  eng::Image image;
  image.name = "offscreen render";
  image.width = static_cast<int>(extent_.width);
  image.height = static_cast<int>(extent_.height);
  image.rgba8.resize(size_t{extent_.width} * extent_.height * 4);
  std::memcpy(image.rgba8.data(), readback_.mapped(), image.rgba8.size());
  return image;
}

}  // namespace eng::vk
