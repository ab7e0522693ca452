#include "engine/vk/offscreen_renderer.h"

#include "engine/vk/vk_result.h"

namespace eng::vk {

Result<OffscreenRenderer> OffscreenRenderer::create(const Context& ctx, const OffscreenOptions& options) {
  OffscreenRenderer r;
  r.ctx_ = &ctx;
  auto layouts = SceneLayouts::create(ctx);
  if (!layouts) return layouts.error();
  r.layouts_ = std::make_unique<SceneLayouts>(std::move(layouts).value());
  r.shaders_ = std::make_unique<ShaderLibrary>(options.shaderSourceDir);
  auto target = OffscreenTarget::create(ctx, options.width, options.height, options.samples);
  if (!target) return target.error();
  r.target_ = std::move(target).value();
  auto scene = SceneRenderer::create(ctx, *r.layouts_, *r.shaders_, r.target_.renderPass(),
                                     r.target_.format().samples, 1);
  if (!scene) return scene.error();
  r.scene_ = std::move(scene).value();
  return r;
}

bool OffscreenRenderer::reloadChangedShaders() { return shaders_->reloadIfChanged() && scene_.refreshPipelines(); }

Result<GpuModel> OffscreenRenderer::upload(const Model& model) const {
  return GpuModel::create(*ctx_, *layouts_, model);
}

Result<eng::Image> OffscreenRenderer::render(const SceneView& view, std::span<const ModelInstance> instances) {
  const VkExtent2D extent = target_.extent();
  const float aspect = float(extent.width) / float(extent.height);
  ENG_TRY(scene_.prepare(0, buildFrameGlobals(view.camera, aspect, view.lights), instances));
  ENG_TRY(target_.render({[&](VkCommandBuffer cmd) { scene_.recordShadowPass(cmd, 0); },
                          [&](VkCommandBuffer cmd) { scene_.record(cmd, 0, extent); }, {}}));
  return target_.readPixels();
}

Result<std::vector<CapturedPrimitive>> OffscreenRenderer::capture(std::span<const ModelInstance> instances) {
  ENG_TRY(scene_.prepareCapture(0, instances));
  ENG_TRY(target_.render({{},
                          [&](VkCommandBuffer cmd) { scene_.recordCapture(cmd, 0); },
                          [](VkCommandBuffer cmd) { SceneRenderer::recordCaptureReadBarrier(cmd); }}));
  return scene_.readCapture(0);
}

}  // namespace eng::vk
