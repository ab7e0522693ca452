#pragma once
// A VkBuffer with its own memory allocation. Host-visible buffers (Upload,
// Readback) stay mapped for their whole life.
#include <cstddef>
#include <span>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/context.h"
#include "engine/vk/unique_handle.h"

namespace eng::vk {

class Buffer {
 public:
  Buffer() = default;
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
  UniqueBuffer buffer_;
  UniqueMemory memory_;
  VkDeviceSize size_ = 0;
  VkMemoryPropertyFlags memoryFlags_ = 0;
  std::byte* mapped_ = nullptr;
};

}  // namespace eng::vk
