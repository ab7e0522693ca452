#pragma once
// VkResult -> readable text, and the Error every failed Vulkan call becomes:
// "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED", code = the VkResult.
#include <string_view>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"

namespace eng::vk {

// The enum's spelling, e.g. "VK_ERROR_DEVICE_LOST"; "VK_RESULT_<n>" when unknown.
std::string_view resultName(VkResult result);

// `call` may be the whole call expression; only the function name is kept.
Error vulkanError(std::string_view call, VkResult result);

// A lost device said plainly -- "the Vulkan device was lost (vkQueueSubmit
// failed: VK_ERROR_DEVICE_LOST): its driver reset or failed, ..." -- since
// nothing drawn on that device can go on; other errors unchanged.
Error explainDeviceLost(const Error& error);

}  // namespace eng::vk

// Returns the Error from the enclosing function when the call fails.
#define ENG_VK_TRY(call)                                                         \
  do {                                                                           \
    if (VkResult eng_vk_result_ = (call); eng_vk_result_ != VK_SUCCESS)          \
      return ::eng::vk::vulkanError(#call, eng_vk_result_);                      \
  } while (0)

