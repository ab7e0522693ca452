#pragma once
// Counts validation-layer messages and routes them to eng::log (warnings and
// errors) and to an optional callback, so tests can fail on any message.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string_view>

#include <vulkan/vulkan.h>

#include "engine/core/log.h"

namespace eng::vk {

using ValidationCallback = std::function<void(LogLevel level, std::string_view message)>;

class ValidationMonitor {
 public:
  explicit ValidationMonitor(ValidationCallback callback = {}) : callback_(std::move(callback)) {}

  // Messages seen so far (warnings + errors).
  uint32_t messageCount() const { return warnings_.load() + errors_.load(); }
  uint32_t errorCount() const { return errors_.load(); }
  uint32_t warningCount() const { return warnings_.load(); }

  void report(LogLevel level, std::string_view message);

  // For VkDebugUtilsMessengerCreateInfoEXT::pfnUserCallback; pUserData is the monitor.
  static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT types,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                      void* userData);

 private:
  std::atomic<uint32_t> warnings_{0};
  std::atomic<uint32_t> errors_{0};
  ValidationCallback callback_;
};

}  // namespace eng::vk
