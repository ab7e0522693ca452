#pragma once
// The graphics pipelines of the scene, built from the shader library's
// current SPIR-V for one render pass: mesh (back-face culled, for either
// winding, and double sided; opaque and alpha-blended), MToon outlines
// (front-face culled), background gradient,
// the key light's shadow-map pass (depth only, its own render pass; plain and
// alpha-masked), the morph pre-pass (compute), and the morph-capture variant
// (vertex stage only, rasteriser discard; absent when the device cannot store
// from vertex shaders).
#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/render_quality.h"
#include "engine/vk/draw/scene_layouts.h"
#include "engine/vk/device/shader_library.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

// How a mesh pipeline treats the base colour's alpha (glTF alphaMode).
enum class AlphaPipeline { Opaque, Mask, Blend };

class ScenePipelines {
 public:
  static Result<ScenePipelines> create(const Context& ctx, const SceneLayouts& layouts, const ShaderLibrary& shaders,
                                       VkRenderPass renderPass, VkSampleCountFlagBits samples,
                                       VkRenderPass shadowPass, const QualitySettings& quality = {});

  // mirrored: the draw's transform has a negative determinant, which glTF
  // says turns counter-clockwise front faces clockwise (culled pipelines only;
  // a double-sided draw tells its sides apart in the shader, DRAW_FLAG_MIRRORED).
  // alpha: Mask may discard fragments; Blend blends, tests depth but does not write it.
  VkPipeline mesh(bool doubleSided, bool mirrored, AlphaPipeline alpha) const {
    const size_t sides = doubleSided ? kDoubleSided : mirrored ? kCulledClockwise : kCulled;
    return mesh_[sides][size_t(alpha)].get();
  }
  // MToon outlines (kDrawFlagToonOutline): the mesh pushed out along its
  // normals with its front faces culled, drawn after the opaque draws.
  VkPipeline outline(bool mirrored, bool masked) const { return outline_[mirrored ? 1 : 0][masked ? 1 : 0].get(); }
  VkPipeline background() const { return background_.get(); }
  VkPipeline capture() const { return capture_.get(); }  // VK_NULL_HANDLE when unsupported
  // Depth only, for the shadow pass; masked: glTF alphaMode MASK, cut out where the base colour is.
  VkPipeline shadow(bool masked) const { return masked ? shadowMasked_.get() : shadow_.get(); }
  VkPipeline morph() const { return morph_.get(); }      // compute: the morph pre-pass (morph.comp)

 private:
  Result<void> createMeshPipelines(const Context& ctx, const SceneLayouts& layouts, const ShaderLibrary& shaders,
                                   VkRenderPass renderPass, VkSampleCountFlagBits samples, const QualitySettings& quality);
  Result<void> createShadowPipelines(const Context& ctx, const SceneLayouts& layouts, const ShaderLibrary& shaders,
                                     VkRenderPass shadowPass);
  // Mesh pipelines by sidedness and alpha mode.
  static constexpr size_t kCulled = 0, kCulledClockwise = 1, kDoubleSided = 2, kMeshSides = 3;
  static constexpr size_t kAlphaPipelines = 3;
  UniquePipeline mesh_[kMeshSides][kAlphaPipelines];
  UniquePipeline outline_[2][2];  // [counter-clockwise, clockwise front faces][opaque, masked]
  UniquePipeline background_;
  UniquePipeline capture_;
  UniquePipeline shadow_;
  UniquePipeline shadowMasked_;
  UniquePipeline morph_;
};

}  // namespace eng::vk
