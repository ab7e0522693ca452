#pragma once
// A test seam for the faults a CPU driver never produces by itself: a lost
// device and a swapchain gone out of date at a chosen frame, so tests can check
// that the programs survive or report them cleanly. The window renderer and the
// headless (offscreen) renderer take the list from their options' `faults` or,
// when that is empty, from the environment variable FACIAL_VK_FAULTS;
// comma-separated:
//
//   device-lost@N   the N-th frame submission (counting from 1; the window's
//                   frames, or the offscreen renderer's frames and captures,
//                   not uploads) reports VK_ERROR_DEVICE_LOST. The work is
//                   really submitted, so the device stays usable for a clean
//                   teardown; only the report lies.
//   out-of-date@N   the N-th image acquisition reports VK_ERROR_OUT_OF_DATE_KHR
//                   without acquiring an image (windows only).
//
// Without faults each hook is one comparison per frame.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"

namespace eng::vk {

inline constexpr const char* kFaultsEnvironmentVariable = "FACIAL_VK_FAULTS";

class FaultInjector {
 public:
  // `origin` names where the list came from in errors and in describe().
  static Result<FaultInjector> parse(std::string_view list, std::string_view origin);
  // `optionFaults` when not empty (`optionName` names it in errors), else
  // FACIAL_VK_FAULTS; an active seam logs one warning naming `user`.
  static Result<FaultInjector> fromOptionOrEnvironment(std::string_view optionFaults, std::string_view optionName,
                                                       std::string_view user);

  bool active() const { return !deviceLostAt_.empty() || !outOfDateAt_.empty(); }
  // "FACIAL_VK_FAULTS=device-lost@40", for the one warning an active seam logs.
  const std::string& describe() const { return description_; }

  // Before an acquisition: VK_SUCCESS to acquire, else the result to report instead.
  VkResult beforeAcquire();
  // After a submission: its real result, or the injected one.
  VkResult afterSubmit(VkResult submitted);

 private:
  std::vector<uint64_t> deviceLostAt_;
  std::vector<uint64_t> outOfDateAt_;
  uint64_t acquisitions_ = 0;
  uint64_t submissions_ = 0;
  std::string description_;
};

}  // namespace eng::vk
