#include "engine/vk/device/device_selection.h"

#include <algorithm>
#include <cctype>

namespace eng::vk {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

int automaticRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

bool matches(const DeviceCandidate& c, const DevicePreference& p) {
  switch (p.kind) {
    case DevicePreference::Kind::Automatic: return true;
    case DevicePreference::Kind::Discrete: return c.type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    case DevicePreference::Kind::Integrated: return c.type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
    case DevicePreference::Kind::Cpu: return c.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    case DevicePreference::Kind::NameContains:
      return lower(c.name).find(lower(p.nameSubstring)) != std::string::npos;
  }
  return false;
}

}  // namespace

DevicePreference DevicePreference::parse(std::string_view text) {
  std::string t = lower(text);
  if (t.empty() || t == "auto") return {};
  if (t == "discrete") return {Kind::Discrete, {}};
  if (t == "integrated") return {Kind::Integrated, {}};
  if (t == "cpu") return {Kind::Cpu, {}};
  return {Kind::NameContains, std::string(text)};
}

std::string DevicePreference::describe() const {
  switch (kind) {
    case Kind::Automatic: return "auto";
    case Kind::Discrete: return "discrete";
    case Kind::Integrated: return "integrated";
    case Kind::Cpu: return "cpu";
    case Kind::NameContains: return "name containing '" + nameSubstring + "'";
  }
  return "?";
}

std::string_view deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

Result<size_t> selectDevice(std::span<const DeviceCandidate> candidates, const DevicePreference& preference) {
  size_t best = candidates.size();
  int bestRank = -1;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const DeviceCandidate& c = candidates[i];
    if (!c.unsuitableReason.empty() || !matches(c, preference)) continue;
    int rank = automaticRank(c.type);
    if (rank > bestRank) {  // strict: among equals the first listed wins
      best = i;
      bestRank = rank;
    }
  }
  if (best < candidates.size()) return best;

  std::string available;
  for (const DeviceCandidate& c : candidates) {
    if (!available.empty()) available += "; ";
    available += c.name + " [" + std::string(deviceTypeName(c.type)) + "]";
    if (!c.unsuitableReason.empty()) available += " unsuitable: " + c.unsuitableReason;
  }
  if (available.empty()) available = "none";
  return makeError(ErrorKind::Device, "no suitable Vulkan device for preference " + preference.describe() +
                   " (devices: " + available + ")");
}

}  // namespace eng::vk
