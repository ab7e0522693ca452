#include "engine/vk/device/memory_type.h"

namespace eng::vk {

std::optional<uint32_t> chooseMemoryType(const VkPhysicalDeviceMemoryProperties& properties,
                                         uint32_t allowedTypeBits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred) {
  auto firstWith = [&](VkMemoryPropertyFlags wanted) -> std::optional<uint32_t> {
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
      if ((allowedTypeBits & (1u << i)) == 0) continue;
      if ((properties.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    return std::nullopt;
  };
  if (preferred != 0) {
    if (auto both = firstWith(required | preferred)) return both;
  }
  return firstWith(required);
}

MemoryFlags memoryFlagsFor(MemoryUsage usage) {
  switch (usage) {
    case MemoryUsage::GpuOnly:
      return {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0};
    case MemoryUsage::Upload:
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT};
    case MemoryUsage::Readback:
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
              VK_MEMORY_PROPERTY_HOST_CACHED_BIT};
  }
  return {};
}

}  // namespace eng::vk
