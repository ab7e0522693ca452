#include "engine/vk/draw/offscreen_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
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
  ENG_TRY(r.createFrames(std::max(1u, options.framesInFlight), options));
  auto scene = SceneRenderer::create(ctx, *r.layouts_, *r.shaders_, r.target().renderPass(),
                                     r.target().format().samples, r.framesInFlight(), options.quality);
  if (!scene) return scene.error();
  r.scene_ = std::move(scene).value();
  auto timestamps = FrameTimestamps::create(ctx);
  if (!timestamps) return timestamps.error();
  r.timestamps_ = std::move(timestamps).value();
  auto passTimes = PassTimestamps::create(ctx, r.framesInFlight(), kPassMarks);
  if (!passTimes) return passTimes.error();
  r.passTimes_ = std::move(passTimes).value();
  r.lodPixelError_ = options.lodPixelError;
  return r;
}

Result<void> OffscreenRenderer::createFrames(uint32_t count, const OffscreenOptions& options) {
  const VkDevice device = ctx_->device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = ctx_->queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  pool_ = UniqueCommandPool(device, pool);
  const VkSampleCountFlagBits samples = qualitySettings(options.quality).samples;
  for (uint32_t i = 0; i < count; ++i) {
    Frame frame;
    frame.target = ENG_TRY_VALUE(OffscreenTarget::create(*ctx_, options.width, options.height,
                                                         samples));
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = pool;
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    ENG_VK_TRY(vkAllocateCommandBuffers(device, &allocInfo, &frame.cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    ENG_VK_TRY(vkCreateFence(device, &fenceInfo, nullptr, &fence));
    frame.done = UniqueFence(device, fence);
    frames_.push_back(std::move(frame));
  }
  return {};
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

Result<GpuModel> OffscreenRenderer::upload(const Model& model, const GpuModelStaging& staging) const {
  return GpuModel::create(*ctx_, *layouts_, model, staging);
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
  ENG_TRY(requireIdle("renderTimed"));
  const VkExtent2D extent = frames_.front().target.extent();
  const float aspect = float(extent.width) / float(extent.height);
  ENG_TRY(scene_.prepare(0, buildFrameGlobals(view.camera, aspect, view.lights), instances,
                         {lodPixelError_, extent.height}));
  const bool studio = view.backdrop.kind == Backdrop::Kind::Studio;
  ENG_TRY(frameSubmitted(frames_.front().target.render({[&](VkCommandBuffer cmd) {
                            timestamps_.recordStart(cmd);
                            scene_.recordShadowPass(cmd, 0);
                          },
                          [&](VkCommandBuffer cmd) { scene_.record(cmd, 0, extent, studio); },
                          [&](VkCommandBuffer cmd) { timestamps_.recordEnd(cmd); }, /*readback=*/false},
                         clearColour(view.backdrop))));
  return timestamps_.readMilliseconds();
}

Result<eng::Image> OffscreenRenderer::render(const SceneView& view, std::span<const ModelInstance> instances) {
  ENG_TRY(requireIdle("render"));
  ENG_TRY(submit(view, instances));
  return collect();
}

Result<void> OffscreenRenderer::requireIdle(const char* call) const {
  if (pending_ == 0) return {};
  return makeError(ErrorKind::InvalidArgument,
                   std::string("offscreen renderer: ") + call + " with frames still in flight (collect() them first)");
}

Result<void> OffscreenRenderer::recordFrame(Frame& frame, uint32_t slot, const SceneView& view) {
  const VkExtent2D extent = frame.target.extent();
  const bool studio = view.backdrop.kind == Backdrop::Kind::Studio;
  ENG_VK_TRY(vkResetCommandBuffer(frame.cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ENG_VK_TRY(vkBeginCommandBuffer(frame.cmd, &begin));
  frame.target.record(frame.cmd,
                      {[&](VkCommandBuffer cmd) {
                         if (frame.timed) passTimes_.mark(cmd, slot, 0);
                         scene_.recordShadowPass(cmd, slot);
                         if (frame.timed) passTimes_.mark(cmd, slot, 1);
                       },
                       [&](VkCommandBuffer cmd) { scene_.record(cmd, slot, extent, studio); },
                       [&](VkCommandBuffer cmd) {
                         if (frame.timed) passTimes_.mark(cmd, slot, 2);
                       }},
                      clearColour(view.backdrop));
  ENG_VK_TRY(vkEndCommandBuffer(frame.cmd));
  return {};
}

Result<void> OffscreenRenderer::submit(const SceneView& view, std::span<const ModelInstance> instances) {
  if (pending_ == framesInFlight())
    return makeError(ErrorKind::InvalidArgument, "offscreen renderer: every frame slot is in flight (collect() one)");
  const uint32_t slot = next_;
  Frame& frame = frames_[slot];
  const VkExtent2D extent = frame.target.extent();
  const float aspect = float(extent.width) / float(extent.height);
  ENG_TRY(scene_.prepare(slot, buildFrameGlobals(view.camera, aspect, view.lights), instances,
                         {lodPixelError_, extent.height}));
  frame.timed = timePasses_;
  ENG_TRY(recordFrame(frame, slot, view));
  frame.transparent = view.backdrop.kind == Backdrop::Kind::Transparent;
  VkFence fence = frame.done.get();
  ENG_VK_TRY(vkResetFences(ctx_->device(), 1, &fence));
  VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  info.commandBufferCount = 1;
  info.pCommandBuffers = &frame.cmd;
  const VkResult submitted = vkQueueSubmit(ctx_->queue(), 1, &info, fence);
  if (submitted == VK_SUCCESS) {
    // In flight even when a test's injected loss is reported below: the
    // teardown waits for it before freeing what it draws with and into.
    next_ = (next_ + 1) % framesInFlight();
    ++pending_;
  }
  return frameSubmitted(submitted == VK_SUCCESS ? Result<void>{} : vulkanError("vkQueueSubmit", submitted));
}

Result<eng::Image> OffscreenRenderer::collect() {
  if (pending_ == 0) return makeError(ErrorKind::InvalidArgument, "offscreen renderer: collect() with no frame in flight");
  using Clock = std::chrono::steady_clock;
  const uint32_t slot = (next_ + framesInFlight() - pending_) % framesInFlight();
  Frame& frame = frames_[slot];
  const Clock::time_point start = Clock::now();
  VkFence fence = frame.done.get();
  const VkResult waited = vkWaitForFences(ctx_->device(), 1, &fence, VK_TRUE, UINT64_MAX);
  --pending_;
  if (waited != VK_SUCCESS) return explainDeviceLost(vulkanError("vkWaitForFences", waited));
  lastTimes_ = {};
  // Read before the clock stops: lavapipe's query read-back waits for the whole device.
  if (std::array<double, kPassMarks - 1> ms{}; frame.timed && passTimes_.read(slot, ms)) {
    lastTimes_.gpuShadowMs = ms[0];
    lastTimes_.gpuViewMs = ms[1];
  }
  const Clock::time_point done = Clock::now();
  eng::Image image = frame.target.readPixels();
  if (frame.transparent) unpremultiplySrgb(image);
  lastTimes_.waitMs = std::chrono::duration<double, std::milli>(done - start).count();
  lastTimes_.readbackMs = std::chrono::duration<double, std::milli>(Clock::now() - done).count();
  return image;
}

void OffscreenRenderer::discardPending() {
  for (; pending_ > 0 && !frames_.empty(); --pending_) {
    VkFence fence = frames_[(next_ + framesInFlight() - pending_) % framesInFlight()].done.get();
    vkWaitForFences(ctx_->device(), 1, &fence, VK_TRUE, UINT64_MAX);  // an error here: the device is lost anyway
  }
}

Result<std::vector<CapturedPrimitive>> OffscreenRenderer::capture(std::span<const ModelInstance> instances) {
  ENG_TRY(requireIdle("capture"));
  ENG_TRY(scene_.prepareCapture(0, instances));
  ENG_TRY(frameSubmitted(frames_.front().target.render({[&](VkCommandBuffer cmd) { scene_.recordMorphPass(cmd, 0); },
                          [&](VkCommandBuffer cmd) { scene_.recordCapture(cmd, 0); },
                          [](VkCommandBuffer cmd) { SceneRenderer::recordCaptureReadBarrier(cmd); }})));
  return scene_.readCapture(0);
}

Result<std::optional<double>> OffscreenRenderer::captureTimed(std::span<const ModelInstance> instances) {
  ENG_TRY(requireIdle("captureTimed"));
  ENG_TRY(scene_.prepareCapture(0, instances));
  ENG_TRY(frameSubmitted(frames_.front().target.render({[&](VkCommandBuffer cmd) {
                            timestamps_.recordStart(cmd);
                            scene_.recordMorphPass(cmd, 0);
                          },
                          [&](VkCommandBuffer cmd) { scene_.recordCapture(cmd, 0); },
                          [&](VkCommandBuffer cmd) { timestamps_.recordEnd(cmd); }, /*readback=*/false})));
  return timestamps_.readMilliseconds();
}

Result<std::optional<double>> OffscreenRenderer::morphTimed(std::span<const ModelInstance> instances) {
  ENG_TRY(requireIdle("morphTimed"));
  ENG_TRY(scene_.prepare(0, FrameGlobals{}, instances));
  ENG_TRY(frameSubmitted(ctx_->submitOneShot([&](VkCommandBuffer cmd) {
    timestamps_.recordStart(cmd);
    scene_.recordMorphPass(cmd, 0);
    timestamps_.recordEnd(cmd);
  })));
  return timestamps_.readMilliseconds();
}

}  // namespace eng::vk
