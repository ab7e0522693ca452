#include "engine/vk/device/fault_injection.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>

#include "engine/core/log.h"

namespace eng::vk {
namespace {

bool contains(const std::vector<uint64_t>& at, uint64_t n) { return std::find(at.begin(), at.end(), n) != at.end(); }

}  // namespace

Result<FaultInjector> FaultInjector::parse(std::string_view list, std::string_view origin) {
  FaultInjector faults;
  const std::string whole(list);
  while (!list.empty()) {
    const size_t comma = list.find(',');
    const std::string_view entry = list.substr(0, comma);
    list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
    if (entry.empty()) continue;
    const size_t at = entry.find('@');
    const std::string_view kind = entry.substr(0, at);
    const std::string_view number = at == std::string_view::npos ? std::string_view{} : entry.substr(at + 1);
    uint64_t n = 0;
    const auto [end, parsed] = std::from_chars(number.data(), number.data() + number.size(), n);
    const bool counted = parsed == std::errc{} && end == number.data() + number.size() && n > 0;
    if (counted && kind == "device-lost") {
      faults.deviceLostAt_.push_back(n);
    } else if (counted && kind == "out-of-date") {
      faults.outOfDateAt_.push_back(n);
    } else {
      return makeError(ErrorKind::InvalidArgument, std::string(origin) + ": cannot read fault '" + std::string(entry) +
                       "' (expected device-lost@N or out-of-date@N, N counted from 1)");
    }
  }
  if (faults.active()) faults.description_ = std::string(origin) + "=" + whole;
  return faults;
}

Result<FaultInjector> FaultInjector::fromOptionOrEnvironment(std::string_view optionFaults,
                                                             std::string_view optionName, std::string_view user) {
  const char* fromEnvironment = std::getenv(kFaultsEnvironmentVariable);
  auto faults = optionFaults.empty() ? parse(fromEnvironment ? fromEnvironment : "", kFaultsEnvironmentVariable)
                                     : parse(optionFaults, optionName);
  if (faults && faults->active())
    logWarning(std::string(user) + ": injecting faults for a test: " + faults->describe());
  return faults;
}

VkResult FaultInjector::beforeAcquire() {
  if (outOfDateAt_.empty()) return VK_SUCCESS;
  return contains(outOfDateAt_, ++acquisitions_) ? VK_ERROR_OUT_OF_DATE_KHR : VK_SUCCESS;
}

VkResult FaultInjector::afterSubmit(VkResult submitted) {
  if (deviceLostAt_.empty()) return submitted;
  return contains(deviceLostAt_, ++submissions_) ? VK_ERROR_DEVICE_LOST : submitted;
}

}  // namespace eng::vk
