#pragma once
// One VkWriteDescriptorSet for a single buffer, texel buffer or image binding: the shape
// every descriptor-set update in the renderer repeats.
#include <vulkan/vulkan.h>

namespace eng::vk {

// The fields every single-descriptor write shares; the caller sets the one pointer.
inline VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  return w;
}

inline VkWriteDescriptorSet bufferWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                                        const VkDescriptorBufferInfo* buffer) {
  VkWriteDescriptorSet w = descriptorWrite(set, binding, type);
  w.pBufferInfo = buffer;
  return w;
}

inline VkWriteDescriptorSet imageWrite(VkDescriptorSet set, uint32_t binding, const VkDescriptorImageInfo* image) {
  VkWriteDescriptorSet w = descriptorWrite(set, binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  w.pImageInfo = image;
  return w;
}

inline VkWriteDescriptorSet texelBufferWrite(VkDescriptorSet set, uint32_t binding, const VkBufferView* view) {
  VkWriteDescriptorSet w = descriptorWrite(set, binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
  w.pTexelBufferView = view;
  return w;
}

}  // namespace eng::vk
