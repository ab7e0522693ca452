#pragma once
// The resource interface every scene pipeline shares (see engine/shaders/
// frame.glsl, morph.glsl, mesh.frag): descriptor set layouts, the pipeline
// layout, the default texture sampler (repeat, trilinear; a model's own
// samplings live in its GpuModel), and the placeholder resources bound where a
// primitive has nothing (no texture, no detail layers, no tangent deltas).
//
//   set 0 (per frame):     0 FrameGlobals UBO, 1 instances, 2 active weights, 3 capture output,
//                          4 key-light shadow map, 5 joint matrices, 6 instance materials,
//                          7 morphed vertices (written by the morph pre-pass), 8 target weights
//                          (texel buffer)
//   set 1 (per primitive): 0-1 sparse deltas (per-vertex offsets, entries with crease
//                          darkening: morph.glsl), 2 rest vertices (the vertex buffer), all
//                          three texel buffers, 3 base colour,
//                          4 detail-layer array, 5 detail-layer parameters, 6 joint influences,
//                          7 metallic-roughness (linear: G roughness, B metallic; white when absent),
//                          8 normal (tangent space; DRAW_FLAG_NORMAL_MAP), 9 occlusion (R; white
//                          when absent), 10 emissive (sRGB; DRAW_FLAG_EMISSIVE_TEXTURE), 11 MToon
//                          matcap (sRGB; DRAW_FLAG_TOON_MATCAP), 12 MToon shading shift (linear, R),
//                          13 MToon rim multiply (sRGB), 14 MToon outline width (linear, G; vertex stage)
//   push constants:        DrawConstants (72 bytes), vertex + fragment; the morph pre-pass has its
//                          own pipeline layout (same sets, push constants for the compute stage)
#include "engine/core/result.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

class SceneLayouts {
 public:
  static Result<SceneLayouts> create(const Context& ctx);

  VkDescriptorSetLayout frameSetLayout() const { return frameSet_.get(); }
  VkDescriptorSetLayout primitiveSetLayout() const { return primitiveSet_.get(); }
  VkPipelineLayout pipelineLayout() const { return pipelineLayout_.get(); }
  VkPipelineLayout morphPipelineLayout() const { return morphPipelineLayout_.get(); }
  VkSampler sampler() const { return sampler_.get(); }

  // 1x1 white sRGB texture: base colour when a material has none (and, white
  // read either way, its metallic-roughness).
  const GpuImage& whiteTexture() const { return white_; }
  // 1x1, one transparent layer: the detail array of materials without layers.
  const GpuImage& emptyDetailArray() const { return emptyDetail_; }
  // 256 zero bytes: storage-buffer bindings that a draw never reads.
  const Buffer& placeholderBuffer() const { return placeholder_; }
  // The same bytes as texel buffers (the morph pre-pass's inputs where a primitive has no deltas).
  VkBufferView placeholderVec4Texels() const { return placeholderVec4_.get(); }
  VkBufferView placeholderFloatTexels() const { return placeholderFloat_.get(); }
  VkBufferView placeholderUintTexels() const { return placeholderUint_.get(); }

 private:
  UniqueDescriptorSetLayout frameSet_;
  UniqueDescriptorSetLayout primitiveSet_;
  UniquePipelineLayout pipelineLayout_;
  UniquePipelineLayout morphPipelineLayout_;
  UniqueSampler sampler_;
  GpuImage white_;
  GpuImage emptyDetail_;
  Buffer placeholder_;
  UniqueBufferView placeholderVec4_;
  UniqueBufferView placeholderFloat_;
  UniqueBufferView placeholderUint_;
};

}  // namespace eng::vk
