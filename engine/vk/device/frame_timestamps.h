#pragma once
// GPU time of one submission: a timestamp written at the start and one at the
// end of its command buffer (vkCmdWriteTimestamp), read back after the
// submission's fence. Only where the device can time the queue
// (timestampPeriod > 0 and the queue family's timestampValidBits > 0);
// elsewhere supported() is false and the recorders do nothing.
//
//   auto stamps = eng::vk::FrameTimestamps::create(ctx);
//   submit: stamps->recordStart(cmd); ...; stamps->recordEnd(cmd);
//   after the fence: std::optional<double> ms = stamps->readMilliseconds();
#include <cstdint>
#include <optional>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class FrameTimestamps {
 public:
  static Result<FrameTimestamps> create(const Context& ctx);

  bool supported() const { return static_cast<bool>(pool_); }
  // First command of the buffer (outside any render pass): resets both
  // queries and writes the start stamp.
  void recordStart(VkCommandBuffer cmd) const;
  // Last command of the buffer: the end stamp, once all earlier work is done.
  void recordEnd(VkCommandBuffer cmd) const;
  // Milliseconds between the stamps of the last completed submission;
  // nullopt when unsupported or nothing was recorded.
  std::optional<double> readMilliseconds() const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  UniqueQueryPool pool_;
  double nanosecondsPerTick_ = 0.0;
  uint64_t validMask_ = 0;  // the bits of a stamp the queue writes
};

}  // namespace eng::vk
