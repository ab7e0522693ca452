// The fault-injection seam's list (engine/vk/device/fault_injection.h): which call
// reports which fault, and a list that cannot be read refused naming it. The
// faults' effect on the window renderer is in window_renderer_test.cpp.
#include "engine/vk/device/fault_injection.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

TEST(FaultInjection, EmptyListInjectsNothing) {
  auto faults = eng::vk::FaultInjector::parse("", "FACIAL_VK_FAULTS");
  ASSERT_TRUE(faults) << faults.error().message;
  EXPECT_FALSE(faults->active());
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(faults->beforeAcquire(), VK_SUCCESS);
    EXPECT_EQ(faults->afterSubmit(VK_SUCCESS), VK_SUCCESS);
    EXPECT_EQ(faults->afterSubmit(VK_ERROR_OUT_OF_DEVICE_MEMORY), VK_ERROR_OUT_OF_DEVICE_MEMORY) << "real results pass";
  }
}

TEST(FaultInjection, FaultsHitTheirCountedCalls) {
  auto faults = eng::vk::FaultInjector::parse("out-of-date@2,device-lost@3,out-of-date@4", "FACIAL_VK_FAULTS");
  ASSERT_TRUE(faults) << faults.error().message;
  EXPECT_TRUE(faults->active());
  EXPECT_EQ(faults->describe(), "FACIAL_VK_FAULTS=out-of-date@2,device-lost@3,out-of-date@4");
  std::vector<VkResult> acquired, submitted;
  for (int i = 0; i < 5; ++i) {
    acquired.push_back(faults->beforeAcquire());
    submitted.push_back(faults->afterSubmit(VK_SUCCESS));
  }
  EXPECT_EQ(acquired, (std::vector<VkResult>{VK_SUCCESS, VK_ERROR_OUT_OF_DATE_KHR, VK_SUCCESS, VK_ERROR_OUT_OF_DATE_KHR,
                                             VK_SUCCESS}));
  EXPECT_EQ(submitted, (std::vector<VkResult>{VK_SUCCESS, VK_SUCCESS, VK_ERROR_DEVICE_LOST, VK_SUCCESS, VK_SUCCESS}));
}

TEST(FaultInjectionValidity, UnreadableFaultIsRefusedNamingItAndWhereItCameFrom) {
  for (const char* bad : {"device-lost", "device-lost@", "device-lost@0", "device-lost@3x", "lost@3", "out-of-date@-1"}) {
    auto faults = eng::vk::FaultInjector::parse(std::string("out-of-date@1,") + bad, "FACIAL_VK_FAULTS");
    ASSERT_FALSE(faults) << bad;
    EXPECT_EQ(faults.error().message, std::string("FACIAL_VK_FAULTS: cannot read fault '") + bad +
                                          "' (expected device-lost@N or out-of-date@N, N counted from 1)");
  }
}

}  // namespace
