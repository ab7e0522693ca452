#pragma once
// Memory-type choice (no VMA in Debian): the first type allowed by the
// resource that has every required flag and, when possible, every preferred
// flag. Vulkan lists types with equal flags fastest-first, so first wins.
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

namespace eng::vk {

std::optional<uint32_t> chooseMemoryType(const VkPhysicalDeviceMemoryProperties& properties,
                                         uint32_t allowedTypeBits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred = 0);

// How a buffer or image is accessed, mapped to required/preferred flags.
enum class MemoryUsage {
  GpuOnly,   // device local; filled through a staging copy
  Upload,    // host writes every frame, GPU reads: host visible + coherent, device local if possible
  Readback,  // GPU writes, host reads: host visible + coherent, cached if possible
};

struct MemoryFlags {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
};
MemoryFlags memoryFlagsFor(MemoryUsage usage);

}  // namespace eng::vk
