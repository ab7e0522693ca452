#pragma once
// Move-only owners of Vulkan handles (one template, one alias per type), so
// every object is destroyed exactly once, in reverse order of declaration.
#include <utility>

#include <vulkan/vulkan.h>

namespace eng::vk {

// A handle destroyed through its parent: vkDestroyX(parent, handle, allocator).
template <class Parent, class Handle, void (*Destroy)(Parent, Handle, const VkAllocationCallbacks*)>
class UniqueHandle {
 public:
  UniqueHandle() = default;
  UniqueHandle(Parent parent, Handle handle) : parent_(parent), handle_(handle) {}
  ~UniqueHandle() { reset(); }

  UniqueHandle(UniqueHandle&& other) noexcept
      : parent_(other.parent_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  UniqueHandle& operator=(UniqueHandle&& other) noexcept {
    if (this != &other) {
      reset();
      parent_ = other.parent_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  UniqueHandle(const UniqueHandle&) = delete;
  UniqueHandle& operator=(const UniqueHandle&) = delete;

  Handle get() const { return handle_; }
  Parent parent() const { return parent_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(parent_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  Parent parent_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

// A handle with no parent: vkDestroyX(handle, allocator).
template <class Handle, void (*Destroy)(Handle, const VkAllocationCallbacks*)>
class UniqueRootHandle {
 public:
  UniqueRootHandle() = default;
  explicit UniqueRootHandle(Handle handle) : handle_(handle) {}
  ~UniqueRootHandle() { reset(); }

  UniqueRootHandle(UniqueRootHandle&& other) noexcept : handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  UniqueRootHandle& operator=(UniqueRootHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  UniqueRootHandle(const UniqueRootHandle&) = delete;
  UniqueRootHandle& operator=(const UniqueRootHandle&) = delete;

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  Handle handle_ = VK_NULL_HANDLE;
};

using UniqueInstance = UniqueRootHandle<VkInstance, vkDestroyInstance>;
using UniqueDevice = UniqueRootHandle<VkDevice, vkDestroyDevice>;
using UniqueSurface = UniqueHandle<VkInstance, VkSurfaceKHR, vkDestroySurfaceKHR>;

using UniqueBuffer = UniqueHandle<VkDevice, VkBuffer, vkDestroyBuffer>;
using UniqueMemory = UniqueHandle<VkDevice, VkDeviceMemory, vkFreeMemory>;
using UniqueImage = UniqueHandle<VkDevice, VkImage, vkDestroyImage>;
using UniqueImageView = UniqueHandle<VkDevice, VkImageView, vkDestroyImageView>;
using UniqueBufferView = UniqueHandle<VkDevice, VkBufferView, vkDestroyBufferView>;
using UniqueSampler = UniqueHandle<VkDevice, VkSampler, vkDestroySampler>;
using UniqueShaderModule = UniqueHandle<VkDevice, VkShaderModule, vkDestroyShaderModule>;
using UniqueDescriptorSetLayout = UniqueHandle<VkDevice, VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = UniqueHandle<VkDevice, VkDescriptorPool, vkDestroyDescriptorPool>;
using UniquePipelineLayout = UniqueHandle<VkDevice, VkPipelineLayout, vkDestroyPipelineLayout>;
using UniquePipeline = UniqueHandle<VkDevice, VkPipeline, vkDestroyPipeline>;
using UniqueRenderPass = UniqueHandle<VkDevice, VkRenderPass, vkDestroyRenderPass>;
using UniqueFramebuffer = UniqueHandle<VkDevice, VkFramebuffer, vkDestroyFramebuffer>;
using UniqueCommandPool = UniqueHandle<VkDevice, VkCommandPool, vkDestroyCommandPool>;
using UniqueFence = UniqueHandle<VkDevice, VkFence, vkDestroyFence>;
using UniqueSemaphore = UniqueHandle<VkDevice, VkSemaphore, vkDestroySemaphore>;
using UniqueSwapchain = UniqueHandle<VkDevice, VkSwapchainKHR, vkDestroySwapchainKHR>;
using UniqueQueryPool = UniqueHandle<VkDevice, VkQueryPool, vkDestroyQueryPool>;

}  // namespace eng::vk
