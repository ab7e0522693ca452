#include "engine/vk/device/validation_monitor.h"

#include <string>

namespace eng::vk {

void ValidationMonitor::report(LogLevel level, std::string_view message) {
  (level == LogLevel::Error ? errors_ : warnings_).fetch_add(1);
  log(level, message);
  if (callback_) callback_(level, message);
}

VKAPI_ATTR VkBool32 VKAPI_CALL ValidationMonitor::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                                VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                                void* userData) {
  auto* monitor = static_cast<ValidationMonitor*>(userData);
  LogLevel level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? LogLevel::Error : LogLevel::Warning;
  std::string message = "vulkan validation: ";
  if (data && data->pMessageIdName) message += std::string("[") + data->pMessageIdName + "] ";
  message += (data && data->pMessage) ? data->pMessage : "(no message)";
  monitor->report(level, message);
  return VK_FALSE;  // never abort the call: behave as without validation
}

}  // namespace eng::vk
