// Physical-device choice rules, on made-up candidate lists.
#include "engine/vk/device/device_selection.h"

#include <vector>

#include <gtest/gtest.h>

namespace {

using eng::vk::DeviceCandidate;
using eng::vk::DevicePreference;
using eng::vk::selectDevice;

const std::vector<DeviceCandidate> kMixed{
    {"llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU, ""},
    {"Intel(R) UHD Graphics 630", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, ""},
    {"NVIDIA GeForce RTX 3080", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, ""},
};

TEST(DevicePreference, ParsesKindsAndNames) {
  EXPECT_EQ(DevicePreference::parse("").kind, DevicePreference::Kind::Automatic);
  EXPECT_EQ(DevicePreference::parse("auto").kind, DevicePreference::Kind::Automatic);
  EXPECT_EQ(DevicePreference::parse("Discrete").kind, DevicePreference::Kind::Discrete);
  EXPECT_EQ(DevicePreference::parse("integrated").kind, DevicePreference::Kind::Integrated);
  EXPECT_EQ(DevicePreference::parse("CPU").kind, DevicePreference::Kind::Cpu);
  const DevicePreference named = DevicePreference::parse("RTX");
  EXPECT_EQ(named.kind, DevicePreference::Kind::NameContains);
  EXPECT_EQ(named.nameSubstring, "RTX");
}

TEST(SelectDevice, AutomaticPrefersDiscreteThenIntegratedThenCpu) {
  EXPECT_EQ(selectDevice(kMixed, {}).value(), 2u);
  const std::vector<DeviceCandidate> noDiscrete(kMixed.begin(), kMixed.begin() + 2);
  EXPECT_EQ(selectDevice(noDiscrete, {}).value(), 1u);
  const std::vector<DeviceCandidate> cpuOnly(kMixed.begin(), kMixed.begin() + 1);
  EXPECT_EQ(selectDevice(cpuOnly, {}).value(), 0u);
}

TEST(SelectDevice, ForcedKindAndNameSubstring) {
  EXPECT_EQ(selectDevice(kMixed, DevicePreference::parse("cpu")).value(), 0u);
  EXPECT_EQ(selectDevice(kMixed, DevicePreference::parse("integrated")).value(), 1u);
  EXPECT_EQ(selectDevice(kMixed, DevicePreference::parse("llvmpipe")).value(), 0u);
  EXPECT_EQ(selectDevice(kMixed, DevicePreference::parse("geforce")).value(), 2u);  // case-insensitive
}

TEST(SelectDevice, SkipsUnsuitableDevices) {
  std::vector<DeviceCandidate> devices = kMixed;
  devices[2].unsuitableReason = "no graphics queue";
  EXPECT_EQ(selectDevice(devices, {}).value(), 1u);
}

TEST(SelectDeviceValidity, NoMatchNamesPreferenceAndDevices) {
  std::vector<DeviceCandidate> devices = kMixed;
  devices[2].unsuitableReason = "Vulkan 1.1 required";
  auto chosen = selectDevice(devices, DevicePreference::parse("discrete"));
  ASSERT_FALSE(chosen);
  const std::string& m = chosen.error().message;
  EXPECT_NE(m.find("discrete"), std::string::npos) << m;
  EXPECT_NE(m.find("llvmpipe"), std::string::npos) << m;
  EXPECT_NE(m.find("Vulkan 1.1 required"), std::string::npos) << m;
}

TEST(SelectDeviceValidity, EmptyListIsAnError) {
  auto chosen = selectDevice({}, {});
  ASSERT_FALSE(chosen);
  EXPECT_NE(chosen.error().message.find("none"), std::string::npos) << chosen.error().message;
}

}  // namespace
