// --quality of the windows (demo, editor): "auto" picks the tier by device.
#include <gtest/gtest.h>

#include "app/view_options.h"

namespace {

TEST(WindowQuality, AutoIsBalancedOnACpuRasteriserAndHighOnAGpu) {
  auto cpu = app::windowQualityOption(app::kWindowQualityAuto, VK_PHYSICAL_DEVICE_TYPE_CPU);
  ASSERT_TRUE(cpu) << cpu.error().message;
  EXPECT_EQ(*cpu, eng::vk::RenderQuality::Balanced);
  for (VkPhysicalDeviceType gpu : {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU}) {
    auto tier = app::windowQualityOption("auto", gpu);
    ASSERT_TRUE(tier) << tier.error().message;
    EXPECT_EQ(*tier, eng::vk::RenderQuality::High);
  }
}

TEST(WindowQuality, NamedTiersAreKeptOnEveryDevice) {
  for (eng::vk::RenderQuality q :
       {eng::vk::RenderQuality::Fast, eng::vk::RenderQuality::Balanced, eng::vk::RenderQuality::High}) {
    auto tier = app::windowQualityOption(std::string(eng::vk::renderQualityName(q)), VK_PHYSICAL_DEVICE_TYPE_CPU);
    ASSERT_TRUE(tier) << tier.error().message;
    EXPECT_EQ(*tier, q);
  }
}

TEST(WindowQualityValidity, UnknownTierNamesTheOptionAndTheValue) {
  auto tier = app::windowQualityOption("ultra", VK_PHYSICAL_DEVICE_TYPE_CPU);
  ASSERT_FALSE(tier);
  EXPECT_EQ(tier.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_NE(tier.error().message.find("--quality 'ultra'"), std::string::npos) << tier.error().message;
}

// Headless commands take "auto" too (`say`'s default): the device decides,
// once the renderer has one (HeadlessRenderOptions::quality).
TEST(HeadlessQuality, AutoIsLeftToTheDeviceAndNamedTiersAreKept) {
  auto automatic = app::qualityOption(app::kQualityAuto);
  ASSERT_TRUE(automatic) << automatic.error().message;
  EXPECT_FALSE(automatic->has_value());
  auto high = app::qualityOption("high");
  ASSERT_TRUE(high) << high.error().message;
  EXPECT_EQ(*high, eng::vk::RenderQuality::High);
  EXPECT_EQ(eng::vk::defaultQuality(VK_PHYSICAL_DEVICE_TYPE_CPU), eng::vk::RenderQuality::Balanced);
  EXPECT_EQ(eng::vk::defaultQuality(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU), eng::vk::RenderQuality::High);
  auto bad = app::qualityOption("ultra");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("--quality 'ultra' is not auto, fast, balanced or high"), std::string::npos)
      << bad.error().message;
}

}  // namespace
