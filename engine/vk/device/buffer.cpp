#include "engine/vk/device/buffer.h"

#include <cstring>
#include <string>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {

Result<Buffer> Buffer::create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
                              const char* debugName) {
  if (size == 0) return makeError(ErrorKind::InvalidArgument, std::string("buffer '") + debugName + "': size must be > 0");
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer raw = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateBuffer(ctx.device(), &info, nullptr, &raw));
  Buffer b;
  b.buffer_ = UniqueBuffer(ctx.device(), raw);
  b.size_ = size;
  ctx.setObjectName(VK_OBJECT_TYPE_BUFFER, raw, debugName);

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), raw, &req);
  auto mem = ctx.allocate(req, memory);
  if (!mem) return mem.error().prefixed(std::string("buffer '") + debugName + "': ");
  b.memory_ = std::move(mem->memory);
  b.memoryFlags_ = mem->flags;
  ENG_VK_TRY(vkBindBufferMemory(ctx.device(), raw, b.memory_.get(), 0));
  if (memory != MemoryUsage::GpuOnly) {
    void* ptr = nullptr;
    ENG_VK_TRY(vkMapMemory(ctx.device(), b.memory_.get(), 0, VK_WHOLE_SIZE, 0, &ptr));
    b.mapped_ = static_cast<std::byte*>(ptr);
  }
  return b;
}

Result<Buffer> Buffer::createWithData(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                                      const char* debugName) {
  auto buffer = create(ctx, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuOnly, debugName);
  if (!buffer) return buffer.error();
  Buffer& dst = buffer.value();
  constexpr VkMemoryPropertyFlags kDirect = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if ((dst.memoryFlags_ & kDirect) == kDirect) {
    void* ptr = nullptr;
    ENG_VK_TRY(vkMapMemory(ctx.device(), dst.memory_.get(), 0, VK_WHOLE_SIZE, 0, &ptr));
    std::memcpy(ptr, bytes.data(), bytes.size());
    vkUnmapMemory(ctx.device(), dst.memory_.get());
    return buffer;
  }

  auto staging = create(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  if (!staging) return staging.error();
  std::memcpy(staging->mapped(), bytes.data(), bytes.size());
  ENG_TRY(ctx.submitOneShot([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, staging->handle(), dst.handle(), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
  }));
  return buffer;
}

Result<UniqueBufferView> createTexelView(const Context& ctx, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size,
                                         VkFormat format) {
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer;
  info.format = format;
  info.offset = offset;
  info.range = size;
  VkBufferView view = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateBufferView(ctx.device(), &info, nullptr, &view));
  return UniqueBufferView(ctx.device(), view);
}

}  // namespace eng::vk
