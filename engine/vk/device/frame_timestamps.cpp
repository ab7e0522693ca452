#include "engine/vk/device/frame_timestamps.h"

#include <array>

#include "engine/vk/device/pass_timestamps.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<FrameTimestamps> FrameTimestamps::create(const Context& ctx) {
  FrameTimestamps t;
  t.device_ = ctx.device();
  const std::optional<TimestampSupport> support = timestampSupport(ctx);
  if (!support) return t;  // not timeable: supported() stays false

  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2;
  VkQueryPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateQueryPool(t.device_, &info, nullptr, &pool));
  t.pool_ = UniqueQueryPool(t.device_, pool);
  t.nanosecondsPerTick_ = support->nanosecondsPerTick;
  t.validMask_ = support->validMask;
  return t;
}

void FrameTimestamps::recordStart(VkCommandBuffer cmd) const {
  if (!pool_) return;
  vkCmdResetQueryPool(cmd, pool_.get(), 0, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 0);
}

void FrameTimestamps::recordEnd(VkCommandBuffer cmd) const {
  if (!pool_) return;
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 1);
}

std::optional<double> FrameTimestamps::readMilliseconds() const {
  if (!pool_) return std::nullopt;
  std::array<uint64_t, 2> stamps{};
  // No WAIT bit: the caller waited for the submission; NOT_READY = never recorded.
  if (vkGetQueryPoolResults(device_, pool_.get(), 0, 2, sizeof(stamps), stamps.data(), sizeof(uint64_t),
                            VK_QUERY_RESULT_64_BIT) != VK_SUCCESS)
    return std::nullopt;
  const uint64_t ticks = ((stamps[1] & validMask_) - (stamps[0] & validMask_)) & validMask_;
  return double(ticks) * nanosecondsPerTick_ * 1e-6;
}

}  // namespace eng::vk
