#pragma once
// Which physical device to use. Pure logic over a list of candidates so the
// rules can be tested without the devices: automatic choice prefers a
// discrete GPU, then integrated, virtual, and finally a CPU implementation
// (lavapipe); FACIAL_DEVICE or ContextOptions::device can force one.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"

namespace eng::vk {

struct DevicePreference {
  enum class Kind { Automatic, Discrete, Integrated, Cpu, NameContains };
  Kind kind = Kind::Automatic;
  std::string nameSubstring;  // Kind::NameContains only (matched case-insensitively)

  // "" / "auto" -> Automatic; "discrete" | "integrated" | "cpu"; anything else
  // is a substring of the device name (e.g. "llvmpipe", "RTX").
  static DevicePreference parse(std::string_view text);
  std::string describe() const;
};

struct DeviceCandidate {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::string unsuitableReason;  // empty when the device can run the renderer
};

std::string_view deviceTypeName(VkPhysicalDeviceType type);

// Index of the chosen candidate, or an error naming the preference and the
// devices that exist (and why unsuitable ones were rejected).
Result<size_t> selectDevice(std::span<const DeviceCandidate> candidates, const DevicePreference& preference);

}  // namespace eng::vk
