// Memory-type choice on a made-up discrete-GPU memory layout.
#include "engine/vk/device/memory_type.h"

#include <gtest/gtest.h>

namespace {

VkPhysicalDeviceMemoryProperties discreteLayout() {
  VkPhysicalDeviceMemoryProperties p{};
  p.memoryTypeCount = 4;
  p.memoryTypes[0].propertyFlags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  p.memoryTypes[1].propertyFlags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  p.memoryTypes[2].propertyFlags =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  p.memoryTypes[3].propertyFlags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                   VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  return p;
}

TEST(ChooseMemoryType, RequiredFlagsFirstMatch) {
  const auto p = discreteLayout();
  EXPECT_EQ(eng::vk::chooseMemoryType(p, 0xF, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0u);
  EXPECT_EQ(eng::vk::chooseMemoryType(p, 0xF, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT), 1u);
}

TEST(ChooseMemoryType, PreferredFlagsWinWhenAvailable) {
  const auto p = discreteLayout();
  const auto upload = eng::vk::memoryFlagsFor(eng::vk::MemoryUsage::Upload);
  EXPECT_EQ(eng::vk::chooseMemoryType(p, 0xF, upload.required, upload.preferred), 3u);  // device-local BAR
  const auto readback = eng::vk::memoryFlagsFor(eng::vk::MemoryUsage::Readback);
  EXPECT_EQ(eng::vk::chooseMemoryType(p, 0xF, readback.required, readback.preferred), 2u);  // cached
}

TEST(ChooseMemoryType, FallsBackToRequiredWhenPreferredMissing) {
  const auto p = discreteLayout();
  const auto upload = eng::vk::memoryFlagsFor(eng::vk::MemoryUsage::Upload);
  // Type 3 not allowed by the resource: plain host-visible memory instead.
  EXPECT_EQ(eng::vk::chooseMemoryType(p, 0x7, upload.required, upload.preferred), 1u);
}

TEST(ChooseMemoryTypeValidity, NothingAllowedOrNothingMatching) {
  const auto p = discreteLayout();
  EXPECT_FALSE(eng::vk::chooseMemoryType(p, 0x0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));
  EXPECT_FALSE(eng::vk::chooseMemoryType(p, 0x1, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT));
  EXPECT_FALSE(eng::vk::chooseMemoryType(p, 0xF, VK_MEMORY_PROPERTY_PROTECTED_BIT));
}

}  // namespace
