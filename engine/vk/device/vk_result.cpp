#include "engine/vk/device/vk_result.h"

#include <string>

namespace eng::vk {

std::string_view resultName(VkResult result) {
  switch (result) {
#define ENG_VK_RESULT_CASE(name) \
  case name:                     \
    return #name;
    ENG_VK_RESULT_CASE(VK_SUCCESS)
    ENG_VK_RESULT_CASE(VK_NOT_READY)
    ENG_VK_RESULT_CASE(VK_TIMEOUT)
    ENG_VK_RESULT_CASE(VK_EVENT_SET)
    ENG_VK_RESULT_CASE(VK_EVENT_RESET)
    ENG_VK_RESULT_CASE(VK_INCOMPLETE)
    ENG_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    ENG_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    ENG_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    ENG_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    ENG_VK_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    ENG_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    ENG_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    ENG_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    ENG_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    ENG_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    ENG_VK_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    ENG_VK_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    ENG_VK_RESULT_CASE(VK_ERROR_UNKNOWN)
    ENG_VK_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    ENG_VK_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    ENG_VK_RESULT_CASE(VK_ERROR_FRAGMENTATION)
    ENG_VK_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    ENG_VK_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
    ENG_VK_RESULT_CASE(VK_ERROR_SURFACE_LOST_KHR)
    ENG_VK_RESULT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    ENG_VK_RESULT_CASE(VK_SUBOPTIMAL_KHR)
    ENG_VK_RESULT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    ENG_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    ENG_VK_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
    ENG_VK_RESULT_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef ENG_VK_RESULT_CASE
    default:
      break;
  }
  thread_local std::string unknown;
  unknown = "VK_RESULT_" + std::to_string(static_cast<int>(result));
  return unknown;
}

Error vulkanError(std::string_view call, VkResult result) {
  std::string_view function = call.substr(0, call.find('('));
  while (!function.empty() && function.back() == ' ') function.remove_suffix(1);
  return makeError(ErrorKind::Device, std::string(function) + " failed: " + std::string(resultName(result)),
                   static_cast<int32_t>(result));
}

Error explainDeviceLost(const Error& error) {
  if (error.code != VK_ERROR_DEVICE_LOST) return error;
  return makeError(ErrorKind::Device,
                   "the Vulkan device was lost (" + error.message +
                       "): its driver reset or failed, or the GPU was removed; nothing more can be drawn",
                   error.code);
}

}  // namespace eng::vk
