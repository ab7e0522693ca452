#pragma once
// GPU time between the passes of a frame, per frame slot (frames in flight
// each keep their own queries): timestamps written between the passes
// (vkCmdWriteTimestamp), read after the slot's fence. Only where the queue can
// time (timestampSupport); elsewhere supported() is false and nothing is recorded.
//
//   auto timer = eng::vk::PassTimestamps::create(ctx, slots, /*marks=*/3);
//   record: timer->mark(cmd, slot, 0) (resets the slot's queries); passes; mark(cmd, slot, 1); ...
//   after the fence: std::array<double, 2> ms; if (timer->read(slot, ms)) ...
#include <cstdint>
#include <optional>
#include <span>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

// How the queue's timestamps read: nullopt where it cannot time
// (timestampPeriod 0 or the queue family's timestampValidBits 0).
struct TimestampSupport {
  double nanosecondsPerTick = 0.0;
  uint64_t validMask = 0;  // the bits of a stamp the queue writes
};
std::optional<TimestampSupport> timestampSupport(const Context& ctx);

class PassTimestamps {
 public:
  static Result<PassTimestamps> create(const Context& ctx, uint32_t slots, uint32_t marks);

  bool supported() const { return static_cast<bool>(pool_); }
  // Mark 0 must be the slot's first command, outside a render pass: it
  // resets the slot's queries. Each mark waits for the work recorded before it.
  void mark(VkCommandBuffer cmd, uint32_t slot, uint32_t mark) const;
  // Milliseconds between consecutive marks of the slot's last completed
  // frame (marks - 1 values into `ms`); false when unsupported or not recorded.
  bool read(uint32_t slot, std::span<double> ms) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  UniqueQueryPool pool_;
  TimestampSupport support_;
  uint32_t marks_ = 0;
};

}  // namespace eng::vk
