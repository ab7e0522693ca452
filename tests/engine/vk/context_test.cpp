// Vulkan context creation: device choice, validation routing, errors as values.
#include "engine/vk/device/context.h"

#include <cstdlib>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include "engine/vk/device/vk_result.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

TEST(Context, CreatesDeviceQueueAndValidation) {
  eng::vk::Context& ctx = vk_test::context();
  EXPECT_NE(ctx.instance(), VK_NULL_HANDLE);
  EXPECT_NE(ctx.physicalDevice(), VK_NULL_HANDLE);
  EXPECT_NE(ctx.device(), VK_NULL_HANDLE);
  EXPECT_NE(ctx.queue(), VK_NULL_HANDLE);
  EXPECT_EQ(ctx.surface(), VK_NULL_HANDLE);
  EXPECT_TRUE(ctx.validationEnabled());
  EXPECT_FALSE(ctx.deviceInfo().name.empty());
  EXPECT_GE(ctx.deviceInfo().maxColorDepthSamples, VK_SAMPLE_COUNT_4_BIT);
  EXPECT_EQ(ctx.validationMessageCount(), 0u);
}

TEST(Context, OneShotSubmissionRuns) {
  eng::vk::Context& ctx = vk_test::context();
  bool recorded = false;
  auto submitted = ctx.submitOneShot([&](VkCommandBuffer cmd) { recorded = cmd != VK_NULL_HANDLE; });
  ASSERT_TRUE(submitted) << submitted.error().message;
  EXPECT_TRUE(recorded);
}

TEST(Context, ForcedCpuDeviceIsChosen) {
  eng::vk::ContextOptions options;
  options.validation = true;
  options.device = "cpu";
  options.onValidationMessage = vk_test::failOnValidationMessage;
  auto ctx = eng::vk::Context::create(options);
  // CI has lavapipe (mesa-vulkan-drivers), a CPU device; a GPU machine
  // without Mesa has none, and the error lists the devices it has ("[cpu]"
  // would be among them).
  if (!ctx && ctx.error().message.find("[cpu]") == std::string::npos)
    GTEST_SKIP() << "no CPU Vulkan device on this machine: " << ctx.error().message;
  ASSERT_TRUE(ctx) << ctx.error().message;
  EXPECT_EQ(ctx->deviceInfo().type, VK_PHYSICAL_DEVICE_TYPE_CPU);
}

TEST(Context, DeviceNameSubstringFromEnvironment) {
  const std::string name = vk_test::context().deviceInfo().name;
  ASSERT_EQ(setenv("FACIAL_DEVICE", name.substr(0, 4).c_str(), 1), 0);
  eng::vk::ContextOptions options;
  options.validation = false;
  auto ctx = eng::vk::Context::create(options);
  unsetenv("FACIAL_DEVICE");
  ASSERT_TRUE(ctx) << ctx.error().message;
  EXPECT_EQ(ctx->deviceInfo().name.substr(0, 4), name.substr(0, 4));
}

TEST(Context, UnknownDeviceIsAReadableError) {
  eng::vk::ContextOptions options;
  options.validation = false;
  options.device = "no-such-gpu-xyz";
  auto ctx = eng::vk::Context::create(options);
  ASSERT_FALSE(ctx);
  EXPECT_EQ(ctx.error().code, VK_ERROR_INITIALIZATION_FAILED);
  EXPECT_NE(ctx.error().message.find("no-such-gpu-xyz"), std::string::npos) << ctx.error().message;
  EXPECT_NE(ctx.error().message.find(vk_test::context().deviceInfo().name), std::string::npos)
      << "the error lists the devices that exist: " << ctx.error().message;
}

TEST(Context, FailingSurfaceFactoryFailsCreation) {
  eng::vk::ContextOptions options;
  options.validation = false;
  options.createSurface = [](VkInstance) -> eng::Result<VkSurfaceKHR> {
    return eng::makeError(eng::ErrorKind::Device, "window system unavailable", VK_ERROR_INITIALIZATION_FAILED);
  };
  auto ctx = eng::vk::Context::create(options);
  ASSERT_FALSE(ctx);
  EXPECT_EQ(ctx.error().message, "window system unavailable");
}

TEST(Context, ValidationMessagesAreCountedAndReported) {
  int reported = 0;
  eng::vk::ContextOptions options;
  options.validation = true;
  options.onValidationMessage = [&](eng::LogLevel level, std::string_view message) {
    ++reported;
    EXPECT_EQ(level, eng::LogLevel::Error);
    EXPECT_NE(message.find("VUID"), std::string_view::npos) << message;
  };
  auto ctx = eng::vk::Context::create(options);
  ASSERT_TRUE(ctx) << ctx.error().message;
  // A deliberate misuse: a buffer of size 0 is invalid usage.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  const eng::LogSink previous = eng::setLogSink([](eng::LogLevel, std::string_view) {});  // keep stderr quiet
  vkCreateBuffer(ctx->device(), &info, nullptr, &buffer);
  eng::setLogSink(previous);
  if (buffer != VK_NULL_HANDLE) vkDestroyBuffer(ctx->device(), buffer, nullptr);
  EXPECT_GE(ctx->validationMessageCount(), 1u);
  EXPECT_EQ(static_cast<uint32_t>(reported), ctx->validationMessageCount());
}

TEST(VulkanError, NamesTheCallAndTheResult) {
  const eng::Error e = eng::vk::vulkanError("vkCreateDevice(physical, &info, nullptr, &device)",
                                            VK_ERROR_INITIALIZATION_FAILED);
  EXPECT_EQ(e.message, "vkCreateDevice failed: VK_ERROR_INITIALIZATION_FAILED");
  EXPECT_EQ(e.code, VK_ERROR_INITIALIZATION_FAILED);
  EXPECT_EQ(eng::vk::resultName(VK_ERROR_OUT_OF_DATE_KHR), "VK_ERROR_OUT_OF_DATE_KHR");
  EXPECT_EQ(eng::vk::resultName(static_cast<VkResult>(-12345)), "VK_RESULT_-12345");
}

}  // namespace
