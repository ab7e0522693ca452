#include "engine/vk/draw/offscreen_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
glm::vec3 srgbToLinear(const glm::vec3& c) { return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)}; }
float linearToSrgb(float c) { return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

// Over a (0,0,0,0) clear, the MSAA resolve averages samples in linear space:
// a pixel a fraction a covered holds (a * colour, a), then sRGB-encoded (alpha
// is not). Straight alpha, as PNG wants: decode, divide by a, encode.
void unpremultiplySrgb(eng::Image& image) {
  std::array<float, 256> decode{};
  for (int i = 0; i < 256; ++i) decode[size_t(i)] = srgbToLinear(float(i) / 255.0f);
  for (size_t p = 0; p + 3 < image.rgba8.size(); p += 4) {
    const uint8_t a = image.rgba8[p + 3];
    if (a == 0) {
      image.rgba8[p] = image.rgba8[p + 1] = image.rgba8[p + 2] = 0;
      continue;
    }
    if (a == 255) continue;
    const float alpha = float(a) / 255.0f;
    for (size_t c = 0; c < 3; ++c) {
      const float straight = std::min(1.0f, decode[image.rgba8[p + c]] / alpha);
      image.rgba8[p + c] = static_cast<uint8_t>(std::lround(linearToSrgb(straight) * 255.0f));
    }
  }
}

}  // namespace

Result<OffscreenRenderer> OffscreenRenderer::create(const Context& ctx, const OffscreenOptions& options) {
  OffscreenRenderer r;
  r.ctx_ = &ctx;
  auto faults = FaultInjector::fromOptionOrEnvironment(options.faults, "OffscreenOptions::faults", "offscreen renderer");
  if (!faults) return faults.error();
  r.faults_ = std::move(faults).value();
  auto layouts = SceneLayouts::create(ctx);
  if (!layouts) return layouts.error();
  r.layouts_ = std::make_unique<SceneLayouts>(std::move(layouts).value());
  r.shaders_ = std::make_unique<ShaderLibrary>(options.shaderSourceDir);
  auto target = OffscreenTarget::create(ctx, options.width, options.height, qualitySettings(options.quality).samples);
  if (!target) return target.error();
  r.target_ = std::move(target).value();
  auto scene = SceneRenderer::create(ctx, *r.layouts_, *r.shaders_, r.target_.renderPass(),
                                     r.target_.format().samples, 1, options.quality);
  if (!scene) return scene.error();
  r.scene_ = std::move(scene).value();
  auto timestamps = FrameTimestamps::create(ctx);
  if (!timestamps) return timestamps.error();
  r.timestamps_ = std::move(timestamps).value();
  r.lodPixelError_ = options.lodPixelError;
  return r;
}

bool OffscreenRenderer::reloadChangedShaders() { return shaders_->reloadIfChanged() && scene_.refreshPipelines(); }

Result<void> OffscreenRenderer::frameSubmitted(Result<void> submitted) {
  if (submitted) {
    if (const VkResult injected = faults_.afterSubmit(VK_SUCCESS); injected != VK_SUCCESS)
      submitted = vulkanError("vkQueueSubmit", injected);
  }
  if (!submitted) return explainDeviceLost(submitted.error());
  return {};
}

Result<GpuModel> OffscreenRenderer::upload(const Model& model) const {
  return GpuModel::create(*ctx_, *layouts_, model);
}

namespace {

glm::vec4 clearColour(const Backdrop& backdrop) {
  if (backdrop.kind == Backdrop::Kind::Solid) return glm::vec4(srgbToLinear(backdrop.srgb), 1.0f);
  if (backdrop.kind == Backdrop::Kind::Transparent) return glm::vec4(0.0f);
  return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

}  // namespace

Result<std::optional<double>> OffscreenRenderer::renderTimed(const SceneView& view,
                                                            std::span<const ModelInstance> instances) {
  const VkExtent2D extent = target_.extent();
  const float aspect = float(extent.width) / float(extent.height);
  ENG_TRY(scene_.prepare(0, buildFrameGlobals(view.camera, aspect, view.lights), instances,
                         {lodPixelError_, extent.height}));
  const bool studio = view.backdrop.kind == Backdrop::Kind::Studio;
  ENG_TRY(frameSubmitted(target_.render({[&](VkCommandBuffer cmd) {
                            timestamps_.recordStart(cmd);
                            scene_.recordShadowPass(cmd, 0);
                          },
                          [&](VkCommandBuffer cmd) { scene_.record(cmd, 0, extent, studio); },
                          [&](VkCommandBuffer cmd) { timestamps_.recordEnd(cmd); }, /*readback=*/false},
                         clearColour(view.backdrop))));
  return timestamps_.readMilliseconds();
}

Result<eng::Image> OffscreenRenderer::render(const SceneView& view, std::span<const ModelInstance> instances) {
  const VkExtent2D extent = target_.extent();
  const float aspect = float(extent.width) / float(extent.height);
  ENG_TRY(scene_.prepare(0, buildFrameGlobals(view.camera, aspect, view.lights), instances,
                         {lodPixelError_, extent.height}));
  const Backdrop& backdrop = view.backdrop;
  const glm::vec4 clear = clearColour(backdrop);
  const bool studio = backdrop.kind == Backdrop::Kind::Studio;
  ENG_TRY(frameSubmitted(target_.render({[&](VkCommandBuffer cmd) { scene_.recordShadowPass(cmd, 0); },
                          [&](VkCommandBuffer cmd) { scene_.record(cmd, 0, extent, studio); }, {}},
                         clear)));
  eng::Image image = target_.readPixels();
  if (backdrop.kind == Backdrop::Kind::Transparent) unpremultiplySrgb(image);
  return image;
}

Result<std::vector<CapturedPrimitive>> OffscreenRenderer::capture(std::span<const ModelInstance> instances) {
  ENG_TRY(scene_.prepareCapture(0, instances));
  ENG_TRY(frameSubmitted(target_.render({[&](VkCommandBuffer cmd) { scene_.recordMorphPass(cmd, 0); },
                          [&](VkCommandBuffer cmd) { scene_.recordCapture(cmd, 0); },
                          [](VkCommandBuffer cmd) { SceneRenderer::recordCaptureReadBarrier(cmd); }})));
  return scene_.readCapture(0);
}

Result<std::optional<double>> OffscreenRenderer::captureTimed(std::span<const ModelInstance> instances) {
  ENG_TRY(scene_.prepareCapture(0, instances));
  ENG_TRY(frameSubmitted(target_.render({[&](VkCommandBuffer cmd) {
                            timestamps_.recordStart(cmd);
                            scene_.recordMorphPass(cmd, 0);
                          },
                          [&](VkCommandBuffer cmd) { scene_.recordCapture(cmd, 0); },
                          [&](VkCommandBuffer cmd) { timestamps_.recordEnd(cmd); }, /*readback=*/false})));
  return timestamps_.readMilliseconds();
}

Result<std::optional<double>> OffscreenRenderer::morphTimed(std::span<const ModelInstance> instances) {
  ENG_TRY(scene_.prepare(0, FrameGlobals{}, instances));
  ENG_TRY(frameSubmitted(ctx_->submitOneShot([&](VkCommandBuffer cmd) {
    timestamps_.recordStart(cmd);
    scene_.recordMorphPass(cmd, 0);
    timestamps_.recordEnd(cmd);
  })));
  return timestamps_.readMilliseconds();
}

}  // namespace eng::vk
