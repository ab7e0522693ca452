#include "engine/vk/present/swapchain.h"

#include <algorithm>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

VkSurfaceFormatKHR chooseFormat(const std::vector<VkSurfaceFormatKHR>& formats) {
  // sRGB formats: the shaders write linear colour and the hardware encodes.
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB}) {
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  }
  return formats.front();
}

}  // namespace

Result<Swapchain> Swapchain::create(const Context& ctx, VkExtent2D framebufferExtent, bool vsync,
                                    Swapchain* previous) {
  const VkPhysicalDevice gpu = ctx.physicalDevice();
  const VkSurfaceKHR surface = ctx.surface();
  if (surface == VK_NULL_HANDLE) return makeError(ErrorKind::InvalidArgument, "swapchain: the context was created without a window surface");
  VkSurfaceCapabilitiesKHR caps;
  ENG_VK_TRY(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps));
  uint32_t formatCount = 0;
  ENG_VK_TRY(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &formatCount, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(formatCount);
  ENG_VK_TRY(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &formatCount, formats.data()));
  if (formats.empty()) return makeError(ErrorKind::Device, "swapchain: the surface reports no formats");
  uint32_t modeCount = 0;
  ENG_VK_TRY(vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &modeCount, nullptr));
  std::vector<VkPresentModeKHR> modes(modeCount);
  ENG_VK_TRY(vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &modeCount, modes.data()));

  const VkSurfaceFormatKHR format = chooseFormat(formats);
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
  if (!vsync && std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end())
    mode = VK_PRESENT_MODE_MAILBOX_KHR;
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
    extent.width = std::clamp(framebufferExtent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(framebufferExtent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) return makeError(ErrorKind::Device, "swapchain: window has no area (minimised)");
  uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

  Swapchain s;
  s.format_ = format.format;
  s.extent_ = extent;
  s.minImageCount_ = std::max(caps.minImageCount, 2u);
  s.transferSource_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  s.transferDestination_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface;
  info.minImageCount = imageCount;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (s.transferSource_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0) |
                    (s.transferDestination_ ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                      -caps.supportedCompositeAlpha);
  info.presentMode = mode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = previous ? previous->handle() : VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateSwapchainKHR(ctx.device(), &info, nullptr, &swapchain));
  s.swapchain_ = UniqueSwapchain(ctx.device(), swapchain);

  uint32_t count = 0;
  ENG_VK_TRY(vkGetSwapchainImagesKHR(ctx.device(), swapchain, &count, nullptr));
  s.images_.resize(count);
  ENG_VK_TRY(vkGetSwapchainImagesKHR(ctx.device(), swapchain, &count, s.images_.data()));
  for (VkImage image : s.images_) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format.format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    ENG_VK_TRY(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
    s.views_.emplace_back(ctx.device(), view);
  }
  return s;
}

Result<Swapchain> Swapchain::createOwnImages(const Context& ctx, VkExtent2D extent, uint32_t count) {
  if (extent.width == 0 || extent.height == 0) return makeError(ErrorKind::Device, "swapchain: window has no area (minimised)");
  Swapchain s;
  s.format_ = VK_FORMAT_B8G8R8A8_SRGB;
  s.extent_ = extent;
  s.minImageCount_ = count;
  s.transferSource_ = s.transferDestination_ = true;
  for (uint32_t i = 0; i < count; ++i) {
    ImageDesc desc;
    desc.extent = extent;
    desc.format = s.format_;
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.debugName = "window image";
    auto image = GpuImage::create(ctx, desc);
    if (!image) return image.error();
    s.images_.push_back(image->handle());
    s.ownImages_.push_back(std::move(image).value());
  }
  return s;
}

}  // namespace eng::vk
