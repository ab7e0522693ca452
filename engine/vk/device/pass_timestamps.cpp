#include "engine/vk/device/pass_timestamps.h"

#include <vector>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

std::optional<TimestampSupport> timestampSupport(const Context& ctx) {
  const float period = ctx.deviceInfo().properties.limits.timestampPeriod;
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, families.data());
  const uint32_t validBits = ctx.queueFamily() < familyCount ? families[ctx.queueFamily()].timestampValidBits : 0;
  if (!(period > 0.0f) || validBits == 0) return std::nullopt;
  return TimestampSupport{double(period), validBits >= 64 ? ~uint64_t{0} : (uint64_t{1} << validBits) - 1};
}

Result<PassTimestamps> PassTimestamps::create(const Context& ctx, uint32_t slots, uint32_t marks) {
  PassTimestamps t;
  t.device_ = ctx.device();
  t.marks_ = marks;
  const std::optional<TimestampSupport> support = timestampSupport(ctx);
  if (!support || slots == 0 || marks < 2) return t;  // not timeable: supported() stays false
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = slots * marks;
  VkQueryPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateQueryPool(t.device_, &info, nullptr, &pool));
  t.pool_ = UniqueQueryPool(t.device_, pool);
  t.support_ = *support;
  return t;
}

void PassTimestamps::mark(VkCommandBuffer cmd, uint32_t slot, uint32_t mark) const {
  if (!pool_) return;
  if (mark == 0) vkCmdResetQueryPool(cmd, pool_.get(), slot * marks_, marks_);
  vkCmdWriteTimestamp(cmd, mark == 0 ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                      pool_.get(), slot * marks_ + mark);
}

bool PassTimestamps::read(uint32_t slot, std::span<double> ms) const {
  if (!pool_ || ms.size() + 1 < marks_) return false;
  std::vector<uint64_t> stamps(marks_);
  // No WAIT bit: the caller waited for the slot's fence; NOT_READY = never recorded.
  if (vkGetQueryPoolResults(device_, pool_.get(), slot * marks_, marks_, stamps.size() * sizeof(uint64_t),
                            stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT) != VK_SUCCESS)
    return false;
  const uint64_t mask = support_.validMask;
  for (uint32_t m = 1; m < marks_; ++m)
    ms[m - 1] = double(((stamps[m] & mask) - (stamps[m - 1] & mask)) & mask) * support_.nanosecondsPerTick * 1e-6;
  return true;
}

}  // namespace eng::vk
