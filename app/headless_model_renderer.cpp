#include "app/headless_model_renderer.h"

#include <cmath>

#include "engine/view/framing_bounds.h"

namespace app {

eng::Result<HeadlessModelRenderer> HeadlessModelRenderer::create(const eng::Model& model,
                                                                 const HeadlessRenderOptions& options) {
  auto context = createContext(options);
  if (!context) return context.error();
  auto r = open(options, std::move(*context));
  if (!r) return r.error();
  if (auto shown = r->show(model, options, nullptr); !shown) return shown.error();
  return r;
}

eng::Result<std::unique_ptr<eng::vk::Context>> HeadlessModelRenderer::createContext(
    const HeadlessRenderOptions& options, bool announce) {
  if (!(options.zoom > 0.0f) || !std::isfinite(options.zoom))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "zoom must be a positive number");
  if (!std::isfinite(options.yawDegrees) || !std::isfinite(options.pitchDegrees))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "yaw and pitch must be finite numbers of degrees");
  eng::vk::ContextOptions contextOptions;
  contextOptions.device = options.device;
  contextOptions.announce = announce;
  auto context = eng::vk::Context::create(contextOptions);
  if (!context) return context.error().prefixed("Vulkan: ");
  return std::make_unique<eng::vk::Context>(std::move(*context));
}

eng::Result<HeadlessModelRenderer> HeadlessModelRenderer::open(const HeadlessRenderOptions& options,
                                                               std::unique_ptr<eng::vk::Context> context) {
  HeadlessModelRenderer r;
  r.context_ = std::move(context);
  auto renderer = eng::vk::OffscreenRenderer::create(
      *r.context_, {.width = options.width, .height = options.height, .quality = options.quality.value_or(eng::vk::defaultQuality(r.context_->deviceInfo().type)),
                    .lodPixelError = options.lodPixelError, .framesInFlight = options.framesInFlight});
  if (!renderer) return renderer.error().prefixed("Vulkan: ");
  r.renderer_ = std::make_unique<eng::vk::OffscreenRenderer>(std::move(*renderer));
  return r;
}

eng::Result<void> HeadlessModelRenderer::show(const eng::Model& model, const HeadlessRenderOptions& options,
                                              const eng::vk::GpuModelStaging* staging) {
  auto gpuModel = staging ? renderer_->upload(model, *staging) : renderer_->upload(model);
  if (!gpuModel) return gpuModel.error();
  gpuModel_ = std::move(*gpuModel);
  view_.camera = eng::OrbitCamera::frame(eng::framingBounds(model, options.framing),
                                         float(options.width) / float(options.height));
  view_.camera.yawDegrees = options.yawDegrees;
  view_.camera.pitchDegrees = options.pitchDegrees;
  view_.camera.zoom = options.zoom;
  view_.backdrop = options.backdrop;
  modelName_ = model.sourcePath;
  return {};
}

eng::Result<eng::Image> HeadlessModelRenderer::render(std::span<const float> weights,
                                                      std::span<const eng::vk::InstanceMaterial> materials) {
  const eng::vk::ModelInstance instance{&gpuModel_, placement_, weights, {}, materials};
  auto image = renderer_->render(view_, {&instance, 1});
  if (!image) return image.error().prefixed(modelName_ + ": rendering failed: ");
  return image;
}

eng::Result<void> HeadlessModelRenderer::checkValidation() const {
  if (auto clean = context_->checkValidation(); !clean)
    return clean.error().prefixed(modelName_ + ": ");
  return {};
}

}  // namespace app
