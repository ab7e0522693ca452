#include "engine/vk/present/window_renderer.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <shared_mutex>
#include <span>
#include <string>

#include "engine/core/log.h"
#include "engine/scene/image_io.h"
#include "engine/vk/present/frame_pacing.h"
#include "engine/vk/draw/light_rig.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

constexpr auto kShaderPollInterval = std::chrono::milliseconds(500);

// The number in environment variable `name` when it is set and a number for
// which `accept` holds; nullopt (with a warning naming the range when set) otherwise.
template <class Accept>
std::optional<float> environmentNumber(const char* name, const char* range, Accept accept) {
  const char* env = std::getenv(name);
  if (!env) return std::nullopt;
  char* end = nullptr;
  const float parsed = std::strtof(env, &end);
  if (end != env && *end == '\0' && accept(parsed)) return parsed;
  logWarning(std::string(name) + "='" + env + "' is not a number in " + range + "; ignored");
  return std::nullopt;
}

// The options' scale, or the automatic one; 1 where a scaled view could not be
// blitted into the swapchain (no transfer usage, no linear blit of its format).
float chooseRenderScale(const Context& ctx, const WindowRendererOptions& options, const Swapchain& swapchain) {
  float scale = options.renderScale;
  if (scale <= 0.0f)
    scale = environmentNumber("FACIAL_RENDER_SCALE", "(0, 1]", [](float v) { return v > 0.0f && v <= 1.0f; })
                .value_or(0.0f);
  if (scale <= 0.0f) scale = ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? kCpuRenderScale : 1.0f;
  scale = std::min(scale, 1.0f);
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), swapchain.format(), &props);
  constexpr VkFormatFeatureFlags kBlit = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                         VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if (!swapchain.canBlitTo() || (props.optimalTilingFeatures & kBlit) != kBlit) return 1.0f;
  return scale;
}

Result<UniqueFramebuffer> createFramebuffer(const Context& ctx, VkRenderPass pass, std::span<const VkImageView> views,
                                            VkExtent2D size) {
  VkFramebufferCreateInfo fbInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fbInfo.renderPass = pass;
  fbInfo.attachmentCount = static_cast<uint32_t>(views.size());
  fbInfo.pAttachments = views.data();
  fbInfo.width = size.width;
  fbInfo.height = size.height;
  fbInfo.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFramebuffer(ctx.device(), &fbInfo, nullptr, &fb));
  return UniqueFramebuffer(ctx.device(), fb);
}

// The options' level-of-detail error, or FACIAL_LOD_PIXEL_ERROR where set (0 draws every triangle).
float chooseLodPixelError(const WindowRendererOptions& options) {
  return environmentNumber("FACIAL_LOD_PIXEL_ERROR", "[0, 64]", [](float v) { return v >= 0.0f && v <= 64.0f; })
      .value_or(options.lodPixelError);
}

// The window's clip space cropped to the view's rectangle: [n0, n1] -> [-1, 1]
// on each axis, and the backdrop's UVs to the same part of the window.
void cropToView(FrameGlobals& globals, const VkRect2D& view, VkExtent2D window) {
  const auto ndc = [](int32_t at, uint32_t size) { return 2.0f * float(at) / float(size) - 1.0f; };
  const float x0 = ndc(view.offset.x, window.width), x1 = ndc(view.offset.x + int32_t(view.extent.width), window.width);
  const float y0 = ndc(view.offset.y, window.height), y1 = ndc(view.offset.y + int32_t(view.extent.height), window.height);
  glm::mat4 crop(1.0f);
  crop[0][0] = 2.0f / (x1 - x0);
  crop[1][1] = 2.0f / (y1 - y0);
  crop[3][0] = -(x0 + x1) / (x1 - x0);
  crop[3][1] = -(y0 + y1) / (y1 - y0);
  globals.proj = crop * globals.proj;
  globals.viewProj = crop * globals.viewProj;
  globals.backdropUv = {float(view.offset.x) / float(window.width), float(view.offset.y) / float(window.height),
                        float(view.extent.width) / float(window.width), float(view.extent.height) / float(window.height)};
}

}  // namespace

WindowRenderer::~WindowRenderer() {
  if (!ctx_) return;
  if (presenter_) presenter_->waitIdle();  // its thread reads presentBuffers_ and waits on frame fences
  presenter_.reset();
  (void)presentPending();  // the last frame, drawn and submitted: shown (and its semaphore waited on)
  vkDeviceWaitIdle(ctx_->device());
}

// One frame in flight's command pool and buffer, fence (signalled: the first
// wait passes) and image-available semaphore.
Result<void> WindowRenderer::createFrameSync(const Context& ctx, FrameSync& f) {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = ctx.queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateCommandPool(ctx.device(), &poolInfo, nullptr, &pool));
  f.pool = UniqueCommandPool(ctx.device(), pool);
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  ENG_VK_TRY(vkAllocateCommandBuffers(ctx.device(), &alloc, &f.cmd));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkFence fence = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateFence(ctx.device(), &fenceInfo, nullptr, &fence));
  f.inFlight = UniqueFence(ctx.device(), fence);
  VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore sem = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateSemaphore(ctx.device(), &semInfo, nullptr, &sem));
  f.imageAvailable = UniqueSemaphore(ctx.device(), sem);
  return {};
}

Result<std::unique_ptr<WindowRenderer>> WindowRenderer::create(const Context& ctx, Window& window,
                                                               const WindowRendererOptions& options) {
  if (ctx.surface() == VK_NULL_HANDLE)
    return makeError(ErrorKind::InvalidArgument, "window renderer: the context has no surface (create it with Window::configureContext)");
  std::unique_ptr<WindowRenderer> r(new WindowRenderer());
  r->ctx_ = &ctx;
  r->window_ = &window;
  r->options_ = options;
  auto faults = FaultInjector::fromOptionOrEnvironment(options.faults, "WindowRendererOptions::faults", "window renderer");
  if (!faults) return faults.error();
  r->faults_ = std::move(faults).value();
  auto layouts = SceneLayouts::create(ctx);
  if (!layouts) return layouts.error();
  r->layouts_ = std::make_unique<SceneLayouts>(std::move(layouts).value());
  r->shaders_ = std::make_unique<ShaderLibrary>(options.shaderSourceDir);

  const char* shm = std::getenv("FACIAL_X11_SHM");
  if (ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU && !(shm && std::string_view(shm) == "0")) {
    auto presenter = X11ShmPresenter::create(window.handle(), window.framebufferExtent(), kFramesInFlight);
    if (presenter) r->presenter_ = std::move(presenter).value();
    else logInfo("window: " + presenter.error().message + "; presenting through the Vulkan swapchain");
  }
  auto swapchain = r->presenter_ ? Swapchain::createOwnImages(ctx, window.framebufferExtent(), kFramesInFlight)
                                 : Swapchain::create(ctx, window.framebufferExtent(), options.vsync);
  if (!swapchain) return swapchain.error();
  r->swapchain_ = std::move(swapchain).value();
  r->viewRect_ = {{0, 0}, r->swapchain_.extent()};
  auto depth = chooseDepthFormat(ctx);
  if (!depth) return depth.error();
  r->format_ = {r->swapchain_.format(), depth.value(), usableSampleCount(ctx, qualitySettings(options.quality).samples)};
  r->renderScale_ = chooseRenderScale(ctx, options, r->swapchain_);
  r->blitView_ = r->renderScale_ < 1.0f;
  r->options_.lodPixelError = chooseLodPixelError(options);
  const bool automaticScale = options.renderScale <= 0.0f && !std::getenv("FACIAL_RENDER_SCALE") &&
                              ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU && r->scaled();
  if (options.adaptiveScale && automaticScale) {
    r->adaptive_.emplace(r->renderScale_, AdaptiveRenderScale::Limits{});
    r->renderScale_ = r->adaptive_->scale();
  }
  auto pass = createSceneRenderPass(ctx, r->format_,
                                    r->scaled() ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : r->presentLayout());
  if (!pass) return pass.error();
  r->renderPass_ = std::move(pass).value();
  if (r->scaled()) {
    auto overlay = createOverlayRenderPass(ctx, r->format_.color, r->presentLayout());
    if (!overlay) return overlay.error();
    r->overlayPass_ = std::move(overlay).value();
  }
  ENG_TRY(r->createSwapchainResources());
  if (r->presenter_) ENG_TRY(r->createPresentBuffers(r->swapchain_.extent()));

  for (FrameSync& f : r->frames_) ENG_TRY(createFrameSync(ctx, f));

  auto scene = SceneRenderer::create(ctx, *r->layouts_, *r->shaders_, r->renderPass_.get(), r->format_.samples,
                                     kFramesInFlight, options.quality);
  if (!scene) return scene.error();
  r->scene_ = std::move(scene).value();

  // ImGui allocates its font set (and user texture sets) from here.
  const VkDescriptorPoolSize imguiSizes{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 64};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 64;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &imguiSizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  r->imguiPool_ = UniqueDescriptorPool(ctx.device(), pool);
  if (options.timeFrames) {
    auto timer = PassTimestamps::create(ctx, kFramesInFlight, WindowFrameTimes::kGpuPasses + 1);
    if (!timer) return timer.error();
    r->passTimes_ = std::move(timer).value();
  }
  r->lastShaderPoll_ = std::chrono::steady_clock::now();
  // Two images acquired at once (this frame's and the one not yet presented) need one more than the minimum.
  r->deferPresent_ = !r->presenter_ && ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU &&
                     r->swapchain_.imageCount() > r->swapchain_.minImageCount();
  return r;
}

Result<void> WindowRenderer::recreateSwapchain() {
  if (presenter_) presenter_->waitIdle();
  ENG_TRY(presentPending());
  vkDeviceWaitIdle(ctx_->device());
  swapchainStale_ = true;  // until everything below succeeded
  framebuffers_.clear();
  sceneFramebuffer_ = {};
  renderFinished_.clear();
  auto swapchain = presenter_ ? Swapchain::createOwnImages(*ctx_, window_->framebufferExtent(), kFramesInFlight)
                             : Swapchain::create(*ctx_, window_->framebufferExtent(), options_.vsync, &swapchain_);
  if (!swapchain) return swapchain.error();
  if (presenter_) {
    const VkExtent2D now = swapchain->extent(), was = presenter_->extent();
    if (now.width != was.width || now.height != was.height) {
      ENG_TRY(presenter_->resize(now));
      ENG_TRY(createPresentBuffers(now));
    }
  }
  if (swapchain->format() != format_.color)
    return makeError(ErrorKind::Device, "swapchain format changed from " + std::to_string(format_.color) + " to " +
                     std::to_string(swapchain->format()) + "; restart the window");
  swapchain_ = std::move(swapchain).value();
  viewRect_ = {{0, 0}, swapchain_.extent()};  // a frame naming a region sets it again
  if (adaptive_) renderScale_ = sharpView_ ? 1.0f : adaptive_->scale();  // sceneExtent() follows the images
  return createSwapchainResources();
}

VkRect2D WindowRenderer::viewRectOf(const FrameInput& frame) const {
  const VkExtent2D window = swapchain_.extent();
  const VkRect2D whole{{0, 0}, window};
  const VkRect2D& r = frame.viewRegion;
  if (!scaled() || r.extent.width == 0 || r.extent.height == 0) return whole;
  const int32_t x0 = std::clamp(r.offset.x, 0, int32_t(window.width) - 1);
  const int32_t y0 = std::clamp(r.offset.y, 0, int32_t(window.height) - 1);
  const int32_t x1 = std::clamp(int32_t(int64_t(r.offset.x) + r.extent.width), x0 + 1, int32_t(window.width));
  const int32_t y1 = std::clamp(int32_t(int64_t(r.offset.y) + r.extent.height), y0 + 1, int32_t(window.height));
  return {{x0, y0}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
}

bool WindowRenderer::viewIsWholeWindow() const {
  const VkExtent2D window = swapchain_.extent();
  return viewRect_.offset.x == 0 && viewRect_.offset.y == 0 && viewRect_.extent.width == window.width &&
         viewRect_.extent.height == window.height;
}

VkExtent2D WindowRenderer::sceneExtent() const {
  const VkExtent2D window = scaled() ? viewRect_.extent : swapchain_.extent();
  if (!scaled()) return window;
  return {std::max(1u, uint32_t(float(window.width) * renderScale_ + 0.5f)),
          std::max(1u, uint32_t(float(window.height) * renderScale_ + 0.5f))};
}

Result<void> WindowRenderer::createSwapchainResources() {
  ENG_TRY(createViewResources());
  for (uint32_t i = 0; i < swapchain_.imageCount(); ++i) {
    std::vector<VkImageView> views;
    const bool msaa = format_.samples != VK_SAMPLE_COUNT_1_BIT;
    if (scaled()) {
      views.push_back(swapchain_.view(i));
    } else {
      views.push_back(msaa ? msaaColor_.view() : swapchain_.view(i));
      views.push_back(depth_.view());
      if (msaa) views.push_back(swapchain_.view(i));
    }
    auto fb = createFramebuffer(*ctx_, scaled() ? overlayPass_.get() : renderPass_.get(), views, swapchain_.extent());
    if (!fb) return fb.error();
    framebuffers_.push_back(std::move(fb).value());
    VkSemaphoreCreateInfo semInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore sem = VK_NULL_HANDLE;
    ENG_VK_TRY(vkCreateSemaphore(ctx_->device(), &semInfo, nullptr, &sem));
    renderFinished_.emplace_back(ctx_->device(), sem);
  }
  swapchainStale_ = false;
  return {};
}

Result<void> WindowRenderer::createViewResources() {
  viewValid_ = false;
  sceneFramebuffer_ = {};
  const VkExtent2D extent = sceneExtent();
  const bool msaa = format_.samples != VK_SAMPLE_COUNT_1_BIT;
  if (msaa) {
    ImageDesc color;
    color.extent = extent;
    color.format = format_.color;
    color.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
    color.samples = format_.samples;
    color.debugName = "window msaa colour";
    auto image = GpuImage::create(*ctx_, color);
    if (!image) return image.error();
    msaaColor_ = std::move(image).value();
  }
  ImageDesc depth;
  depth.extent = extent;
  depth.format = format_.depth;
  depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  depth.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  depth.samples = format_.samples;
  depth.debugName = "window depth";
  auto depthImage = GpuImage::create(*ctx_, depth);
  if (!depthImage) return depthImage.error();
  depth_ = std::move(depthImage).value();

  if (scaled()) {
    ImageDesc color;
    color.extent = extent;
    color.format = format_.color;
    color.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    color.debugName = "window 3D view";
    auto image = GpuImage::create(*ctx_, color);
    if (!image) return image.error();
    sceneColor_ = std::move(image).value();
    std::vector<VkImageView> views{msaa ? msaaColor_.view() : sceneColor_.view(), depth_.view()};
    if (msaa) views.push_back(sceneColor_.view());
    auto fb = createFramebuffer(*ctx_, renderPass_.get(), views, extent);
    if (!fb) return fb.error();
    sceneFramebuffer_ = std::move(fb).value();
  }
  return {};
}

Result<bool> WindowRenderer::followStillness(uint64_t contentKey) {
  const auto now = std::chrono::steady_clock::now();
  if (contentKey != lastKey_) stillSince_ = now;
  stillFrames_ = contentKey == lastKey_ ? stillFrames_ + 1 : 0;
  lastKey_ = contentKey;
  if (!adaptive_) return false;
  const bool sharp = options_.sharpWhenStillFor >= 0.0f && stillFrames_ >= kStillFramesBeforeSharp &&
                     std::chrono::duration<float>(now - stillSince_).count() >= options_.sharpWhenStillFor;
  if (sharp == sharpView_) return false;
  sharpView_ = sharp;
  vkDeviceWaitIdle(ctx_->device());  // the other frame in flight may still read the view's images
  renderScale_ = sharp ? 1.0f : adaptive_->scale();
  lastPresented_ = {};  // the next frame is not the adaptive scale's to time
  adaptive_->restart();
  ENG_TRY(createViewResources());
  return true;
}

Result<GpuModel> WindowRenderer::upload(const Model& model) const { return GpuModel::create(*ctx_, *layouts_, model); }

ImGuiVulkanInfo WindowRenderer::imguiInfo() const {
  ImGuiVulkanInfo info;
  info.instance = ctx_->instance();
  info.physicalDevice = ctx_->physicalDevice();
  info.device = ctx_->device();
  info.queueFamily = ctx_->queueFamily();
  info.queue = ctx_->queue();
  info.descriptorPool = imguiPool_.get();
  info.renderPass = scaled() ? overlayPass_.get() : renderPass_.get();
  info.subpass = 0;
  info.minImageCount = swapchain_.minImageCount();
  info.imageCount = swapchain_.imageCount();
  info.msaaSamples = scaled() ? VK_SAMPLE_COUNT_1_BIT : format_.samples;
  return info;
}

bool WindowRenderer::reloadChangedShaders() {
  lastShaderPoll_ = std::chrono::steady_clock::now();
  if (!shaders_->reloadIfChanged()) return false;
  return scene_.refreshPipelines();
}

// A swapchain of the window's size, rebuilt where it went stale; false when
// there is nothing to draw into (minimised) this frame.
Result<bool> WindowRenderer::readySwapchain() {
  switch (decideFrameAction(window_->framebufferExtent(), swapchain_.extent(), swapchainStale_)) {
    case FrameAction::Skip:
      lastPresented_ = {};
      window_->waitEvents(0.05);
      return false;
    case FrameAction::RecreateSwapchain:
      if (auto rebuilt = recreateSwapchain(); !rebuilt) {
        // Minimised between the size query and the rebuild: not an error, try again later.
        const VkExtent2D now = window_->framebufferExtent();
        if (now.width == 0 || now.height == 0) return false;
        return rebuilt.error();
      }
      break;
    case FrameAction::Draw:
      break;
  }
  return true;
}

Result<FrameResult> WindowRenderer::drawFrame(const FrameInput& frame) {
  if (options_.hotReload && std::chrono::steady_clock::now() - lastShaderPoll_ >= kShaderPollInterval)
    reloadChangedShaders();
  if (window_->takeResized()) swapchainStale_ = true;
  if (auto ready = readySwapchain(); !ready || !*ready) {
    if (!ready) return ready.error();
    return FrameResult::Skipped;
  }
  if (!frame.screenshot.empty() && !swapchain_.canCopyFrom())
    return makeError(ErrorKind::Device, "screenshot " + frame.screenshot.string() + ": this surface's images cannot be copied from");

  const VkDevice device = ctx_->device();
  const uint32_t slot = frameIndex_ % kFramesInFlight;
  FrameSync& f = frames_[slot];
  VkFence fence = f.inFlight.get();
  StepClock clock(times_, options_.timeFrames);
  ENG_VK_TRY(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
  if (presenter_) presenter_->waitSlot(slot);  // done reading the slot's pixels
  if (options_.timeFrames) times_.gpuTimed = frameIndex_ >= kFramesInFlight && passTimes_.read(slot, times_.gpu);
  clock.lap(WindowFrameTimes::WaitSlot);

  const VkExtent2D extent = swapchain_.extent();
  if (const VkRect2D rect = viewRectOf(frame); std::memcmp(&rect, &viewRect_, sizeof rect) != 0) {
    vkDeviceWaitIdle(device);  // the other frame in flight may still read the view's images
    viewRect_ = rect;
    ENG_TRY(createViewResources());
  }
  const float aspect = float(extent.width) / float(extent.height);
  FrameGlobals globals = buildFrameGlobals(frame.view.camera, aspect, frame.view.lights);
  if (!viewIsWholeWindow()) cropToView(globals, viewRect_, extent);
  ENG_TRY(scene_.prepare(slot, globals, frame.instances, {options_.lodPixelError * renderScale_, sceneExtent().height}));
  auto rescaled = followStillness(scene_.contentKey(slot));
  if (!rescaled) return rescaled.error();
  if (*rescaled)  // the levels of detail follow the new size
    ENG_TRY(scene_.prepare(slot, globals, frame.instances, {options_.lodPixelError * renderScale_, sceneExtent().height}));
  // Nothing changed since the view image was drawn: blit it again (and the overlay over it).
  const bool reuseView = scaled() && viewValid_ && viewKey_ == lastKey_;
  clock.lap(WindowFrameTimes::Upload);

  uint32_t image = slot;  // presenter_: the slot's own image, free once its fence is
  VkResult acquired = faults_.beforeAcquire();
  if (acquired == VK_SUCCESS && !presenter_)
    acquired = vkAcquireNextImageKHR(device, swapchain_.handle(), UINT64_MAX, f.imageAvailable.get(), VK_NULL_HANDLE,
                                     &image);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    swapchainStale_ = true;
    return FrameResult::Skipped;
  }
  if (acquired == VK_SUBOPTIMAL_KHR) swapchainStale_ = true;  // still presentable: draw, rebuild next frame
  else if (acquired != VK_SUCCESS) return vulkanError("vkAcquireNextImageKHR", acquired);
  ENG_VK_TRY(vkResetFences(device, 1, &fence));
  clock.lap(WindowFrameTimes::Acquire);

  if (!frame.screenshot.empty()) ENG_TRY(ensureScreenshotBuffer(extent));
  ENG_TRY(recordFrame(f, slot, image, frame, reuseView));
  clock.lap(WindowFrameTimes::Record);
  // The frame before this one, now that this one has its image: the X
  // server draws it while this frame renders. (Acquired after it was sent,
  // the image would wait for the server, which the acquire asks.)
  ENG_TRY(presentPending());
  clock.lap(WindowFrameTimes::Present);
  ENG_TRY(submitAndPresent(f, image, clock));

  lastSlot_ = slot;
  ++frameIndex_;
  lastViewReused_ = reuseView;
  viewKey_ = lastKey_;
  viewValid_ = scaled();
  // Only frames drawn at the adaptive scale time it.
  if (adaptive_ && !reuseView && !sharpView_) adaptRenderScale();
  else lastPresented_ = {};
  if (!frame.screenshot.empty()) {
    ENG_VK_TRY(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    ENG_TRY(saveScreenshot(frame.screenshot));
  }
  return FrameResult::Presented;
}

Result<void> WindowRenderer::ensureScreenshotBuffer(VkExtent2D extent) {
  const VkDeviceSize bytes = VkDeviceSize{extent.width} * extent.height * 4;
  if (screenshotBuffer_ && screenshotBuffer_.size() >= bytes) return {};
  auto buffer = Buffer::create(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "screenshot readback");
  if (!buffer) return buffer.error();
  screenshotBuffer_ = std::move(buffer).value();
  return {};
}

Result<void> WindowRenderer::recordFrame(const FrameSync& f, uint32_t slot, uint32_t image, const FrameInput& frame,
                                         bool reuseView) {
  VkCommandBuffer cmd = f.cmd;
  ENG_VK_TRY(vkResetCommandPool(ctx_->device(), f.pool.get(), 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ENG_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  passTimes_.mark(cmd, slot, 0);
  if (reuseView) {
    passTimes_.mark(cmd, slot, 1);
    passTimes_.mark(cmd, slot, 2);
    recordUpscaleAndOverlay(cmd, image, frame, slot);
    if (!frame.screenshot.empty()) recordScreenshotCopy(cmd, image);
    if (presenter_) recordPresentCopy(cmd, image);
    ENG_VK_TRY(vkEndCommandBuffer(cmd));
    return {};
  }
  scene_.recordShadowPass(cmd, slot);
  passTimes_.mark(cmd, slot, 1);
  std::array<VkClearValue, 3> clears{};
  clears[0].color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  clears[1].depthStencil = {1.0f, 0};
  clears[2].color = {{0.0f, 0.0f, 0.0f, 1.0f}};
  const VkExtent2D viewExtent = sceneExtent();
  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = renderPass_.get();
  pass.framebuffer = scaled() ? sceneFramebuffer_.get() : framebuffers_[image].get();
  pass.renderArea = {{0, 0}, viewExtent};
  pass.clearValueCount = format_.samples != VK_SAMPLE_COUNT_1_BIT ? 3 : 2;
  pass.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  scene_.record(cmd, slot, viewExtent);
  if (!scaled() && frame.overlay) frame.overlay(cmd);
  vkCmdEndRenderPass(cmd);
  passTimes_.mark(cmd, slot, 2);
  if (scaled()) {
    recordUpscaleAndOverlay(cmd, image, frame, slot);
  } else {
    passTimes_.mark(cmd, slot, 3);  // nothing blitted; the overlay was drawn in the view's pass
    passTimes_.mark(cmd, slot, 4);
  }
  if (!frame.screenshot.empty()) recordScreenshotCopy(cmd, image);
  if (presenter_) recordPresentCopy(cmd, image);
  ENG_VK_TRY(vkEndCommandBuffer(cmd));
  return {};
}

void WindowRenderer::recordPresentCopy(VkCommandBuffer cmd, uint32_t slot) const {
  // The frame's passes leave the image in TRANSFER_SRC_OPTIMAL (presentLayout()), their writes before transfers.
  const VkExtent2D extent = swapchain_.extent();
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, swapchain_.image(slot), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, presentBuffers_[slot].handle(),
                         1, &copy);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
}

Result<void> WindowRenderer::createPresentBuffers(VkExtent2D extent) {
  const VkDeviceSize bytes = VkDeviceSize{extent.width} * extent.height * 4;
  for (Buffer& buffer : presentBuffers_) {
    auto created = Buffer::create(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "window frame for X11");
    if (!created) return created.error();
    buffer = std::move(created).value();
  }
  return {};
}

void WindowRenderer::recordScreenshotCopy(VkCommandBuffer cmd, uint32_t image) const {
  const VkExtent2D extent = swapchain_.extent();
  const VkImage swapImage = swapchain_.image(image);
  recordImageBarrier(cmd, {swapImage, VK_IMAGE_ASPECT_COLOR_BIT, presentLayout(),
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT});
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, swapImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, screenshotBuffer_.handle(), 1, &copy);
  recordImageBarrier(cmd, {swapImage, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           presentLayout(), VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0});
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
}

Result<void> WindowRenderer::submitAndPresent(const FrameSync& f, uint32_t image, StepClock& clock) {
  VkCommandBuffer cmd = f.cmd;
  const VkSemaphore waitSemaphore = f.imageAvailable.get();
  const VkSemaphore signalSemaphore = renderFinished_[image].get();
  const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = presenter_ ? 0 : 1;  // presenter_: no acquire, no presentation engine
  submit.pWaitSemaphores = &waitSemaphore;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  submit.signalSemaphoreCount = presenter_ ? 0 : 1;
  submit.pSignalSemaphores = &signalSemaphore;
  if (const VkResult submitted = faults_.afterSubmit(vkQueueSubmit(ctx_->queue(), 1, &submit, f.inFlight.get()));
      submitted != VK_SUCCESS)
    return vulkanError("vkQueueSubmit", submitted);
  clock.lap(WindowFrameTimes::Submit);
  if (presenter_) {
    presenter_->present(image, presentBuffers_[image].mapped(), [device = ctx_->device(), fence = f.inFlight.get()] {
      // On the presenter's thread, while this one may make other contexts
      // (an editor's export): see contextLifetimeMutex.
      std::shared_lock lock(contextLifetimeMutex());
      // Only a lost device fails this; the frame then shows whatever the buffer held.
      (void)vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
    });
    clock.lap(WindowFrameTimes::Present);
    return {};
  }
  if (deferPresent_) {
    pendingPresent_ = image;
    return {};
  }
  ENG_TRY(present(image));
  clock.lap(WindowFrameTimes::Present);
  return {};
}

Result<void> WindowRenderer::present(uint32_t image) {
  const VkSwapchainKHR swapchain = swapchain_.handle();
  const VkSemaphore rendered = renderFinished_[image].get();
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &image;
  const VkResult presented = vkQueuePresentKHR(ctx_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) swapchainStale_ = true;
  else if (presented != VK_SUCCESS) return vulkanError("vkQueuePresentKHR", presented);
  return {};
}

Result<void> WindowRenderer::finishPresenting() {
  if (presenter_) presenter_->waitIdle();
  return presentPending();
}

Result<void> WindowRenderer::presentPending() {
  if (!pendingPresent_) return {};
  const uint32_t image = *pendingPresent_;
  pendingPresent_.reset();
  return present(image);
}

void WindowRenderer::adaptRenderScale() {
  const auto now = std::chrono::steady_clock::now();
  const auto previous = lastPresented_;
  lastPresented_ = now;
  if (previous == std::chrono::steady_clock::time_point{}) return;
  if (!adaptive_->addFrame(std::chrono::duration<double>(now - previous).count())) return;
  swapchainStale_ = true;   // the next frame rebuilds the view's images at the new scale (recreateSwapchain)
  lastPresented_ = {};      // and is not timed: the rebuild is not the frame's cost
  adaptive_->restart();
}

void WindowRenderer::recordUpscaleAndOverlay(VkCommandBuffer cmd, uint32_t image, const FrameInput& frame,
                                             uint32_t slot) const {
  const VkImage target = swapchain_.image(image);
  // Chained to the acquire semaphore's wait (colour-attachment-output stage).
  recordImageBarrier(cmd, {target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT});
  const VkExtent2D from = sceneExtent(), to = viewRect_.extent, window = swapchain_.extent();
  if (!viewIsWholeWindow()) {
    // Under the overlay around the view: the backdrop's middle colour (a
    // clear is a fill on a CPU device; clearing only the bands around the view
    // in the overlay's pass draws them, and cost more than the whole fill).
    const glm::vec3 middle =
        frame.surroundColour.value_or(0.5f * (frame.view.lights.backgroundTop + frame.view.lights.backgroundBottom));
    const VkClearColorValue colour{{middle.r, middle.g, middle.b, 1.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &all);
  }
  // The scene pass left the view in TRANSFER_SRC_OPTIMAL, its writes ordered before transfers.
  if (from.width == to.width && from.height == to.height) {
    // A sharp still view: copied, not filtered (a CPU device's blit decodes and encodes every sRGB texel).
    VkImageCopy copy{};
    copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.dstOffset = {viewRect_.offset.x, viewRect_.offset.y, 0};
    copy.extent = {to.width, to.height, 1};
    vkCmdCopyImage(cmd, sceneColor_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  } else {
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(from.width), int32_t(from.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = {viewRect_.offset.x, viewRect_.offset.y, 0};
    blit.dstOffsets[1] = {viewRect_.offset.x + int32_t(to.width), viewRect_.offset.y + int32_t(to.height), 1};
    vkCmdBlitImage(cmd, sceneColor_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
  }
  passTimes_.mark(cmd, slot, 3);
  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = overlayPass_.get();
  pass.framebuffer = framebuffers_[image].get();
  pass.renderArea = {{0, 0}, window};
  vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  if (frame.overlay) {
    const VkViewport viewport{0.0f, 0.0f, float(window.width), float(window.height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, window};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    frame.overlay(cmd);
  }
  vkCmdEndRenderPass(cmd);
  passTimes_.mark(cmd, slot, 4);
}

Result<void> WindowRenderer::saveScreenshot(const std::filesystem::path& path) {
  const VkExtent2D extent = swapchain_.extent();
  std::vector<uint8_t> rgba(size_t{extent.width} * extent.height * 4);
  std::memcpy(rgba.data(), screenshotBuffer_.mapped(), rgba.size());
  const VkFormat f = swapchain_.format();
  if (f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM) {
    for (size_t i = 0; i < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
  } else if (f != VK_FORMAT_R8G8B8A8_SRGB && f != VK_FORMAT_R8G8B8A8_UNORM) {
    return makeError(ErrorKind::Device, "screenshot " + path.string() + ": swapchain format " + std::to_string(f) +
                     " is not 8-bit RGBA/BGRA");
  }
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;  // the window is opaque
  return writePng(path, static_cast<int>(extent.width), static_cast<int>(extent.height), rgba);
}

}  // namespace eng::vk
