#include "engine/vk/device/context.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "engine/core/log.h"
#include "engine/vk/device/device_selection.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kApiVersion = VK_API_VERSION_1_1;

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v && (std::strcmp(v, "1") == 0 || std::strcmp(v, "true") == 0 || std::strcmp(v, "on") == 0);
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, exts.data());
  return std::any_of(exts.begin(), exts.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// A queue family with graphics (and presentation to `surface`, if any).
std::optional<uint32_t> findQueueFamily(VkPhysicalDevice device, VkSurfaceKHR surface) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0 || families[i].queueCount == 0) continue;
    if (surface != VK_NULL_HANDLE) {
      VkBool32 present = VK_FALSE;
      if (vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present) != VK_SUCCESS || !present) continue;
    }
    return i;
  }
  return std::nullopt;
}

VkSampleCountFlagBits highestCommonSampleCount(const VkPhysicalDeviceLimits& limits) {
  VkSampleCountFlags counts = limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
  for (VkSampleCountFlagBits bit : {VK_SAMPLE_COUNT_64_BIT, VK_SAMPLE_COUNT_32_BIT, VK_SAMPLE_COUNT_16_BIT,
                                    VK_SAMPLE_COUNT_8_BIT, VK_SAMPLE_COUNT_4_BIT, VK_SAMPLE_COUNT_2_BIT}) {
    if (counts & bit) return bit;
  }
  return VK_SAMPLE_COUNT_1_BIT;
}

std::string whyUnsuitable(VkPhysicalDevice device, const VkPhysicalDeviceProperties& props, VkSurfaceKHR surface) {
  if (props.apiVersion < kApiVersion) return "Vulkan 1.1 required";
  if (!findQueueFamily(device, surface))
    return surface != VK_NULL_HANDLE ? "no graphics queue that can present to the window" : "no graphics queue";
  if (surface != VK_NULL_HANDLE && !hasDeviceExtension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
    return "no VK_KHR_swapchain";
  return {};
}

}  // namespace

std::shared_mutex& contextLifetimeMutex() {
  static std::shared_mutex mutex;
  return mutex;
}

Context::Context() = default;
Context::Context(Context&&) noexcept = default;
Context::~Context() { destroy(); }

// Everything the context made, in reverse order, under the lifetime mutex.
void Context::destroy() {
  if (!instance_) return;  // moved from, or never made
  std::unique_lock lock(contextLifetimeMutex());
  if (device_) vkDeviceWaitIdle(device_.get());
  oneShotFence_.reset();
  oneShotPool_.reset();
  device_.reset();
  surface_.reset();
  messenger_.reset();
  instance_.reset();
}

Result<Context> Context::create(const ContextOptions& options) {
  Context ctx;  // before the lock: a context that failed halfway is destroyed after it is released
  std::unique_lock lock(contextLifetimeMutex());
  ctx.validation_ = std::make_unique<ValidationMonitor>(options.onValidationMessage);
  ctx.validationEnabled_ = options.validation.value_or(envFlag("FACIAL_VALIDATION"));
  if (ctx.validationEnabled_ && !hasLayer(kValidationLayer))
    return makeError(ErrorKind::Unsupported, std::string("Vulkan validation was requested but ") + kValidationLayer +
                         " is not installed (Debian package vulkan-validationlayers)",
                     VK_ERROR_LAYER_NOT_PRESENT);
  if (auto made = ctx.createInstance(options); !made) return made.error();
  if (auto chosen = ctx.choosePhysicalDevice(options); !chosen) return chosen.error();
  if (auto made = ctx.createDevice(); !made) return made.error();
  if (options.announce) ctx.announce();
  return ctx;
}

void Context::announce() const {
  logInfo("vulkan: using " + info_.name + " (" + std::string(deviceTypeName(info_.type)) + ")" +
          (validationEnabled_ ? ", validation on" : ""));
}

// The instance (with the validation layer and its messenger when on) and the
// window's surface, if the options make one.
Result<void> Context::createInstance(const ContextOptions& options) {
  std::vector<const char*> extensions;
  for (const std::string& e : options.instanceExtensions) extensions.push_back(e.c_str());
  if (validationEnabled_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  std::vector<const char*> layers;
  if (validationEnabled_) layers.push_back(kValidationLayer);

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = options.applicationName.c_str();
  app.pEngineName = "facial";
  app.apiVersion = kApiVersion;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  instanceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  instanceInfo.ppEnabledExtensionNames = extensions.data();
  instanceInfo.enabledLayerCount = static_cast<uint32_t>(layers.size());
  instanceInfo.ppEnabledLayerNames = layers.data();
  // Chained so messages from vkCreateInstance/vkDestroyInstance are caught too.
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo = debugMessengerInfo(validation_.get());
  if (validationEnabled_) instanceInfo.pNext = &messengerInfo;
  VkInstance instance = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateInstance(&instanceInfo, nullptr, &instance));
  instance_ = UniqueInstance(instance);

  if (validationEnabled_) {
    auto messenger = DebugMessenger::create(instance, validation_.get());
    if (!messenger) return messenger.error();
    messenger_ = std::move(messenger).value();
    setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
  }

  if (options.createSurface) {
    auto surface = options.createSurface(instance);
    if (!surface) return surface.error();
    surface_ = UniqueSurface(instance, surface.value());
  }
  return {};
}

// The device the options or FACIAL_DEVICE prefer among the suitable ones, and
// what it supports (info_).
Result<void> Context::choosePhysicalDevice(const ContextOptions& options) {
  uint32_t deviceCount = 0;
  ENG_VK_TRY(vkEnumeratePhysicalDevices(instance_.get(), &deviceCount, nullptr));
  std::vector<VkPhysicalDevice> devices(deviceCount);
  ENG_VK_TRY(vkEnumeratePhysicalDevices(instance_.get(), &deviceCount, devices.data()));
  std::vector<DeviceCandidate> candidates;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(d, &props);
    candidates.push_back({props.deviceName, props.deviceType, whyUnsuitable(d, props, surface_.get())});
  }
  std::string preferenceText = options.device;
  if (preferenceText.empty()) {
    if (const char* env = std::getenv("FACIAL_DEVICE")) preferenceText = env;
  }
  auto chosen = selectDevice(candidates, DevicePreference::parse(preferenceText));
  if (!chosen) return makeError(chosen.error().kind, chosen.error().message, VK_ERROR_INITIALIZATION_FAILED);
  VkPhysicalDevice physical = devices[chosen.value()];
  physicalDevice_ = physical;

  DeviceInfo& info = info_;
  vkGetPhysicalDeviceProperties(physical, &info.properties);
  vkGetPhysicalDeviceMemoryProperties(physical, &info.memory);
  info.name = info.properties.deviceName;
  info.type = info.properties.deviceType;
  info.maxColorDepthSamples = highestCommonSampleCount(info.properties.limits);
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical, &supported);
  info.vertexPipelineStores = supported.vertexPipelineStoresAndAtomics == VK_TRUE;
  info.samplerAnisotropy = supported.samplerAnisotropy == VK_TRUE;
  return {};
}

// The logical device with its one queue, and the one-shot command pool and fence.
Result<void> Context::createDevice() {
  queueFamily_ = *findQueueFamily(physicalDevice_, surface_.get());
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures enabled{};
  enabled.vertexPipelineStoresAndAtomics = info_.vertexPipelineStores ? VK_TRUE : VK_FALSE;
  enabled.samplerAnisotropy = info_.samplerAnisotropy ? VK_TRUE : VK_FALSE;
  std::vector<const char*> deviceExtensions;
  if (surface_.get() != VK_NULL_HANDLE) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.pEnabledFeatures = &enabled;
  deviceInfo.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
  deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
  VkDevice device = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device));
  device_ = UniqueDevice(device);
  vkGetDeviceQueue(device, queueFamily_, 0, &queue_);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VkCommandPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  oneShotPool_ = UniqueCommandPool(device, pool);
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFence(device, &fenceInfo, nullptr, &fence));
  oneShotFence_ = UniqueFence(device, fence);
  return {};
}

Result<uint32_t> Context::memoryTypeFor(const VkMemoryRequirements& requirements, MemoryUsage usage) const {
  MemoryFlags flags = memoryFlagsFor(usage);
  auto type = chooseMemoryType(info_.memory, requirements.memoryTypeBits, flags.required, flags.preferred);
  if (!type)
    return makeError(ErrorKind::Device, "no Vulkan memory type with flags 0x" + std::to_string(flags.required) + " among allowed types 0x" +
                         std::to_string(requirements.memoryTypeBits),
                     VK_ERROR_OUT_OF_DEVICE_MEMORY);
  return *type;
}

Result<Context::Allocation> Context::allocate(const VkMemoryRequirements& requirements, MemoryUsage usage) const {
  auto type = memoryTypeFor(requirements, usage);
  if (!type) return type.error();
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type.value();
  VkDeviceMemory memory = VK_NULL_HANDLE;
  ENG_VK_TRY(vkAllocateMemory(device(), &info, nullptr, &memory));
  return Allocation{UniqueMemory(device(), memory), info_.memory.memoryTypes[type.value()].propertyFlags};
}

Result<void> Context::submitOneShot(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = oneShotPool_.get();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  ENG_VK_TRY(vkAllocateCommandBuffers(device(), &allocInfo, &cmd));
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } freeOnExit{device(), oneShotPool_.get(), cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ENG_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  ENG_VK_TRY(vkEndCommandBuffer(cmd));
  VkFence fence = oneShotFence_.get();
  ENG_VK_TRY(vkResetFences(device(), 1, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  ENG_VK_TRY(vkQueueSubmit(queue_, 1, &submit, fence));
  ENG_VK_TRY(vkWaitForFences(device(), 1, &fence, VK_TRUE, UINT64_MAX));
  return {};
}

void Context::setObjectName(VkObjectType type, uint64_t handle, const char* name) const {
  if (!setObjectName_ || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  setObjectName_(device(), &info);
}

}  // namespace eng::vk
