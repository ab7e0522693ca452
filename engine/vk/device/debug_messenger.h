#pragma once
// Owner of a VkDebugUtilsMessengerEXT (its create/destroy entry points are
// extension functions fetched from the instance).
#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/validation_monitor.h"

namespace eng::vk {

// Severities: warning + error; types: general, validation, performance.
VkDebugUtilsMessengerCreateInfoEXT debugMessengerInfo(ValidationMonitor* monitor);

class DebugMessenger {
 public:
  DebugMessenger() = default;
  static Result<DebugMessenger> create(VkInstance instance, ValidationMonitor* monitor);
  ~DebugMessenger() { reset(); }
  DebugMessenger(DebugMessenger&& other) noexcept { *this = std::move(other); }
  DebugMessenger& operator=(DebugMessenger&& other) noexcept;
  DebugMessenger(const DebugMessenger&) = delete;
  DebugMessenger& operator=(const DebugMessenger&) = delete;

  void reset();

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroy_ = nullptr;
};

}  // namespace eng::vk
