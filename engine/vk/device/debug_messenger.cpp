#include "engine/vk/device/debug_messenger.h"

#include <utility>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

VkDebugUtilsMessengerCreateInfoEXT debugMessengerInfo(ValidationMonitor* monitor) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &ValidationMonitor::debugCallback;
  info.pUserData = monitor;
  return info;
}

Result<DebugMessenger> DebugMessenger::create(VkInstance instance, ValidationMonitor* monitor) {
  auto createFn = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  auto destroyFn = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (!createFn || !destroyFn)
    return makeError(ErrorKind::Device, "vkCreateDebugUtilsMessengerEXT failed: VK_ERROR_EXTENSION_NOT_PRESENT",
                     VK_ERROR_EXTENSION_NOT_PRESENT);
  VkDebugUtilsMessengerCreateInfoEXT info = debugMessengerInfo(monitor);
  DebugMessenger m;
  ENG_VK_TRY(createFn(instance, &info, nullptr, &m.messenger_));
  m.instance_ = instance;
  m.destroy_ = destroyFn;
  return m;
}

DebugMessenger& DebugMessenger::operator=(DebugMessenger&& other) noexcept {
  if (this != &other) {
    reset();
    instance_ = other.instance_;
    messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
    destroy_ = other.destroy_;
  }
  return *this;
}

void DebugMessenger::reset() {
  if (messenger_ != VK_NULL_HANDLE) destroy_(instance_, messenger_, nullptr);
  messenger_ = VK_NULL_HANDLE;
}

}  // namespace eng::vk
