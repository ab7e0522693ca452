#pragma once
// A VkBuffer with its own memory allocation. Host-visible buffers (Upload,
// Readback) stay mapped for their whole life.
#include <cstddef>
#include <span>
#include <utility>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

// A view of `size` bytes from `offset` as texels of `format`.
Result<UniqueBufferView> createTexelView(const Context& ctx, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size,
                                         VkFormat format);

class Buffer {
 public:
  Buffer() = default;
  Buffer(Buffer&&) noexcept = default;
  // The buffer is destroyed before the memory it is bound to is freed.
  Buffer& operator=(Buffer&& other) noexcept {
    if (this != &other) {
      buffer_.reset();
      memory_ = std::move(other.memory_);
      buffer_ = std::move(other.buffer_);
      size_ = other.size_;
      memoryFlags_ = other.memoryFlags_;
      mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
  }
  // size must be > 0.
  static Result<Buffer> create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                               const char* debugName);
  // A GpuOnly buffer holding `bytes` (written directly when the memory is host
  // visible, as on integrated GPUs and lavapipe, else through a staging copy).
  static Result<Buffer> createWithData(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                                       const char* debugName);

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  explicit operator bool() const { return static_cast<bool>(buffer_); }
  // Start of the mapping (nullptr for GpuOnly buffers).
  std::byte* mapped() const { return mapped_; }

 private:
  UniqueMemory memory_;  // declared first: destroyed after the buffer
  UniqueBuffer buffer_;
  VkDeviceSize size_ = 0;
  VkMemoryPropertyFlags memoryFlags_ = 0;
  std::byte* mapped_ = nullptr;
};

}  // namespace eng::vk
