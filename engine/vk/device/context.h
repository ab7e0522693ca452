#pragma once
// The Vulkan context: instance (+ debug messenger when validation is on),
// the chosen physical device, one logical device with one graphics queue
// (that also presents when a surface is given), memory-type choice and
// one-shot command submission. Move-only; destroys everything in order.
//
//   auto ctx = eng::vk::Context::create({});            // headless
//   if (!ctx) { eng::logError(ctx.error().message); }
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/debug_messenger.h"
#include "engine/vk/device/memory_type.h"
#include "engine/vk/device/unique_handle.h"
#include "engine/vk/device/validation_monitor.h"

namespace eng::vk {

struct ContextOptions {
  std::string applicationName = "facial";
  // Validation layer + messenger. Unset: on when the environment has FACIAL_VALIDATION=1.
  std::optional<bool> validation;
  // "discrete" | "integrated" | "cpu" | a device-name substring; empty: the
  // FACIAL_DEVICE environment variable, else automatic (discrete GPU first).
  std::string device;
  // Extra instance extensions (a window system's surface extensions).
  std::vector<std::string> instanceExtensions;
  // Creates the presentation surface once the instance exists; the chosen
  // device must then be able to present to it. Empty for headless use.
  std::function<Result<VkSurfaceKHR>(VkInstance)> createSurface;
  // Called for every validation message, after it is logged and counted.
  ValidationCallback onValidationMessage;
  // Logs which device is used (announce(), Info level) once it is made.
  bool announce = true;
};

// Making or destroying a Vulkan instance or device while another thread
// calls Vulkan can crash under the Khronos validation layer Debian bookworm
// ships (1.3.239): it finds its per-instance and per-device data in a map that
// every call reads and that making or destroying either writes, without a lock
// (KhronosGroup/Vulkan-ValidationLayers#4391; here a jump to address 0 in the
// editor while a video export made its renderers beside the window's
// presenter thread). Context holds this mutex exclusively while it makes or
// destroys its instance and device (contexts made side by side, which
// drivers have raced on too, queue up); a thread that calls Vulkan while
// another may make or destroy a context holds it shared around those calls.
std::shared_mutex& contextLifetimeMutex();

struct DeviceInfo {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  VkPhysicalDeviceProperties properties{};  // limits included
  VkPhysicalDeviceMemoryProperties memory{};
  bool vertexPipelineStores = false;        // enabled: the morph-capture pipeline needs it
  bool samplerAnisotropy = false;           // enabled when present
  VkSampleCountFlagBits maxColorDepthSamples = VK_SAMPLE_COUNT_1_BIT;
};

class Context {
 public:
  static Result<Context> create(const ContextOptions& options = {});

  Context(Context&&) noexcept;
  Context& operator=(Context&&) = delete;  // a live context is destroyed under contextLifetimeMutex
  ~Context();

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_.get(); }
  uint32_t queueFamily() const { return queueFamily_; }
  VkQueue queue() const { return queue_; }
  VkSurfaceKHR surface() const { return surface_.get(); }  // VK_NULL_HANDLE when headless
  const DeviceInfo& deviceInfo() const { return info_; }
  bool validationEnabled() const { return validationEnabled_; }
  // Logs "vulkan: using DEVICE (TYPE)[, validation on]" (Info).
  void announce() const;
  // Validation messages seen so far (0 when validation is off).
  uint32_t validationMessageCount() const { return validation_->messageCount(); }
  // An error counting the validation messages so far (each was logged as it
  // came), ok when there were none: how a program ends a validation run.
  Result<void> checkValidation() const {
    if (const uint32_t messages = validationMessageCount(); messages > 0)
      return makeError(ErrorKind::Device, std::to_string(messages) + " Vulkan validation message(s) (logged above)");
    return {};
  }

  // A memory type for `requirements` with the flags `usage` needs.
  Result<uint32_t> memoryTypeFor(const VkMemoryRequirements& requirements, MemoryUsage usage) const;
  struct Allocation {
    UniqueMemory memory;
    VkMemoryPropertyFlags flags = 0;  // of the chosen memory type
  };
  Result<Allocation> allocate(const VkMemoryRequirements& requirements, MemoryUsage usage) const;

  // Records `record` into a fresh command buffer, submits it and waits.
  // Not thread-safe: one-shot work comes from the thread that owns the context.
  Result<void> submitOneShot(const std::function<void(VkCommandBuffer)>& record) const;

  // Names an object for validation messages and debuggers; no-op without debug utils.
  void setObjectName(VkObjectType type, uint64_t handle, const char* name) const;
  template <class Handle>
  void setObjectName(VkObjectType type, Handle handle, const char* name) const {
    setObjectName(type, reinterpret_cast<uint64_t>(handle), name);
  }

 private:
  Context();
  // The steps of create(), in order.
  Result<void> createInstance(const ContextOptions& options);
  Result<void> choosePhysicalDevice(const ContextOptions& options);
  Result<void> createDevice();
  void destroy();

  std::unique_ptr<ValidationMonitor> validation_;  // stable address: the messenger's user data
  UniqueInstance instance_;
  DebugMessenger messenger_;
  UniqueSurface surface_;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  UniqueDevice device_;
  uint32_t queueFamily_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  UniqueCommandPool oneShotPool_;
  UniqueFence oneShotFence_;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
  bool validationEnabled_ = false;
};

}  // namespace eng::vk
