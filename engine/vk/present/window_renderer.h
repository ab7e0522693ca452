#pragma once
// Renders model instances into a window: swapchain (recreated on resize,
// idle while minimised), 4x MSAA, two frames in flight, an overlay hook that
// records after the scene (ImGui), screenshots of a presented frame, and
// shader hot reload from engine/shaders. The 3D view may render at a lower
// resolution than the window and be blitted up (renderScale: a CPU
// rasteriser's cost is per pixel); the overlay stays at full resolution.
//
//   auto window = eng::vk::Window::create({});
//   eng::vk::ContextOptions options;
//   (*window)->configureContext(options);
//   auto ctx = eng::vk::Context::create(options);
//   auto renderer = eng::vk::WindowRenderer::create(*ctx, **window);
//   auto gpuModel = (*renderer)->upload(model);
//   // ImGui: ImGui_ImplGlfw_InitForVulkan(window->handle(), true); then fill
//   // ImGui_ImplVulkan_InitInfo from (*renderer)->imguiInfo() (see ImGuiVulkanInfo).
//   while (!(*window)->shouldClose()) {
//     (*window)->pollEvents();
//     eng::vk::FrameInput frame{view, {&instance, 1}};
//     frame.overlay = [](VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); };
//     if (auto r = (*renderer)->drawFrame(frame); !r) { /* report r.error() */ }
//   }
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/fault_injection.h"
#include "engine/vk/present/frame_pacing.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/device/pass_timestamps.h"
#include "engine/vk/draw/gpu_model.h"
#include "engine/vk/device/render_pass.h"
#include "engine/vk/draw/render_quality.h"
#include "engine/vk/draw/scene_layouts.h"
#include "engine/vk/draw/scene_renderer.h"
#include "engine/vk/draw/scene_view.h"
#include "engine/vk/device/shader_library.h"
#include "engine/vk/present/swapchain.h"
#include "engine/vk/present/x11_shm_presenter.h"
#include "engine/vk/present/window.h"

namespace eng::vk {

// A level of detail may stray this far (pixels of the window, whatever the
// 3D view's scale: the level stays put while the dynamic resolution moves)
// from the full mesh. Half a pixel drops the built-in head's skin from
// 50k to 12k triangles in a 1280x800 window; at a whole pixel of its 832x520
// view (6k) the simplifier, blind to texture coordinates and vertex colours,
// smears the painted eyelid lines and the baked shadow at the mouth corners.
inline constexpr float kWindowLodPixelError = 0.5f;

struct WindowRendererOptions {
  // Multisampling, shadow map and shading terms (render_quality.h).
  RenderQuality quality = RenderQuality::High;
  bool vsync = true;
  bool hotReload = true;  // poll the shader sources twice a second
  // The 3D view's resolution relative to the window's, in (0, 1]; 0 picks one:
  // FACIAL_RENDER_SCALE if set, else 1 on a GPU and kCpuRenderScale on a CPU
  // device (lavapipe). Falls back to 1
  // where the swapchain cannot be blitted to.
  float renderScale = 0.0f;
  // Level of detail (SceneRenderer's LodPolicy): each draw uses the coarsest
  // level of its primitive that strays at most this many window pixels from
  // the full mesh; 0 draws every triangle.
  float lodPixelError = kWindowLodPixelError;
  // With the automatic scale on a CPU device: follow the measured frame time
  // between AdaptiveRenderScale's floor and ceiling (frame_pacing.h), aiming
  // at 30 frames/s; false keeps kCpuRenderScale.
  bool adaptiveScale = true;
  // With the adaptive scale: a 3D view still for this many seconds (and at
  // least kStillFramesBeforeSharp frames) is drawn once at full resolution.
  // Long enough that a pause in speech does not trigger it: the full-size
  // frame costs several adaptive ones on a CPU device. Negative: never.
  float sharpWhenStillFor = 1.0f;
  std::filesystem::path shaderSourceDir = defaultShaderSourceDir();
  // Injected faults for tests (fault_injection.h); empty: FACIAL_VK_FAULTS, if set.
  std::string faults;
  // Time each frame's steps (lastFrameTimes): the CPU's with a clock, the
  // passes with GPU timestamps where the queue has them. Off by default:
  // lavapipe's query read-back waits for the whole device, so frames no
  // longer overlap while it is on.
  bool timeFrames = false;
};

// Where one frame's time went (WindowRendererOptions::timeFrames), in ms.
struct WindowFrameTimes {
  enum Cpu : uint8_t { WaitSlot, Upload, Acquire, Record, Submit, Present, kCpuSteps };
  enum Gpu : uint8_t { MorphAndShadow, View3D, Blit, Overlay, kGpuPasses };
  std::array<double, kCpuSteps> cpu{};
  std::array<double, kGpuPasses> gpu{};  // of the last frame its slot completed
  bool cpuTimed = false;                 // timeFrames is on
  bool gpuTimed = false;                 // ... and the queue timed the passes
};
inline constexpr const char* kWindowCpuStepNames[WindowFrameTimes::kCpuSteps] = {
    "wait for a frame slot", "upload (weights, materials)", "acquire image", "record commands", "submit",
    "present"};
inline constexpr const char* kWindowGpuPassNames[WindowFrameTimes::kGpuPasses] = {
    "GPU: morph + shadow map", "GPU: 3D view + resolve", "GPU: blit up", "GPU: ImGui overlay"};

// Everything ImGui_ImplVulkan_Init needs (copy into ImGui_ImplVulkan_InitInfo;
// pass renderPass as its second argument).
struct ImGuiVulkanInfo {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;  // owned by the renderer, for ImGui's own sets
  VkRenderPass renderPass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  uint32_t minImageCount = 2;
  uint32_t imageCount = 2;
  VkSampleCountFlagBits msaaSamples = VK_SAMPLE_COUNT_1_BIT;
};

// The automatic renderScale on a CPU device: a 1280x800 window's 3D view at
// 832x520, about 30 frames/s of the built-in head on lavapipe (2 cores).
inline constexpr float kCpuRenderScale = 0.65f;
// With the adaptive scale: frames in a row with nothing changed in the 3D
// view (and WindowRendererOptions::sharpWhenStillFor seconds) after which it
// is drawn once at full resolution (and re-presented until something changes).
inline constexpr uint32_t kStillFramesBeforeSharp = 3;

using OverlayRecorder = std::function<void(VkCommandBuffer)>;

struct FrameInput {
  SceneView view;
  std::span<const ModelInstance> instances;
  OverlayRecorder overlay;            // recorded inside the render pass after the scene
  // The window pixels the 3D view shows, where the overlay covers the rest
  // (an editor's panels); empty: the whole window. The picture inside is the
  // whole window's cropped (the camera still frames the whole window), and a
  // 3D view drawn at a lower scale and blitted up spends nothing outside;
  // there the overlay is drawn over the backdrop's middle colour.
  VkRect2D viewRegion{};
  // The colour (linear RGB) the window is filled with around viewRegion,
  // under the overlay; unset: the backdrop's middle colour. Panels that
  // cover all of it can leave their backgrounds to this fill (a CPU device
  // then blends none of those pixels twice).
  std::optional<glm::vec3> surroundColour;
  std::filesystem::path screenshot;   // non-empty: also write this frame (overlay included) as PNG
};

enum class FrameResult { Presented, Skipped };

// Laps of one frame's CPU steps into WindowFrameTimes::cpu (when on).
class StepClock {
 public:
  StepClock(WindowFrameTimes& times, bool on) : times_(on ? &times : nullptr), last_(std::chrono::steady_clock::now()) {
    times.cpuTimed = on;
  }
  void lap(WindowFrameTimes::Cpu step) {
    if (!times_) return;
    const auto now = std::chrono::steady_clock::now();
    times_->cpu[step] = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }

 private:
  WindowFrameTimes* times_;
  std::chrono::steady_clock::time_point last_;
};

class WindowRenderer {
 public:
  // `ctx` must have been created with window.configureContext(); both must outlive the renderer.
  static Result<std::unique_ptr<WindowRenderer>> create(const Context& ctx, Window& window,
                                                       const WindowRendererOptions& options = {});
  ~WindowRenderer();
  WindowRenderer(const WindowRenderer&) = delete;
  WindowRenderer& operator=(const WindowRenderer&) = delete;

  Result<GpuModel> upload(const Model& model) const;
  ImGuiVulkanInfo imguiInfo() const;

  // Draws and presents one frame. Skipped while the window is minimised (after
  // a short wait for events, so a loop around it does not spin).
  Result<FrameResult> drawFrame(const FrameInput& frame);

  VkExtent2D extent() const { return swapchain_.extent(); }
  // What the 3D view renders at (extent() scaled by renderScale()).
  VkExtent2D sceneExtent() const;
  float renderScale() const { return renderScale_; }
  bool adaptiveScale() const { return adaptive_.has_value(); }
  // The last frame re-presented the 3D view of the frame before (nothing in
  // it changed: SceneRenderer::contentKey) instead of drawing it again.
  bool lastViewReused() const { return lastViewReused_; }
  FrameStats lastFrameStats() const { return scene_.stats(lastSlot_); }
  const WindowFrameTimes& lastFrameTimes() const { return times_; }
  const ShaderLibrary& shaders() const { return *shaders_; }
  // Frames go to the window through X11 shared memory on a thread of the
  // renderer's (a CPU device: x11_shm_presenter.h), not the Vulkan swapchain.
  bool presentsThroughX11Shm() const { return presenter_ != nullptr; }
  // Every frame drawn so far is in the window (a deferred present made, the X11 thread idle).
  Result<void> finishPresenting();
  // Polls the shader sources now and rebuilds pipelines if they changed and compile.
  bool reloadChangedShaders();

 private:
  static constexpr uint32_t kFramesInFlight = 2;
  struct FrameSync {
    UniqueCommandPool pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    UniqueFence inFlight;
    UniqueSemaphore imageAvailable;
  };

  WindowRenderer() = default;
  static Result<void> createFrameSync(const Context& ctx, FrameSync& f);
  Result<void> recreateSwapchain();
  Result<bool> readySwapchain();
  // MSAA colour, depth, framebuffers and semaphores for the current swapchain.
  Result<void> createSwapchainResources();
  // The 3D view is drawn into its own image and blitted into the swapchain's
  // (fixed at creation: a CPU device's scale below 1, which a still view
  // may raise to 1 for a while).
  bool scaled() const { return blitView_; }
  // The view's images (multisampled colour, depth, the blitted view) at sceneExtent().
  Result<void> createViewResources();
  // After prepare: counts still frames, and in the adaptive mode switches to
  // the full resolution once the view has been still for a few frames and
  // back at the first change (rebuilding the view's images). True when the
  // scale changed (the frame is prepared again for it).
  Result<bool> followStillness(uint64_t contentKey);
  // Scaled: the 3D view blitted into the swapchain image, then the overlay pass.
  void recordUpscaleAndOverlay(VkCommandBuffer cmd, uint32_t image, const FrameInput& frame, uint32_t slot) const;
  // Scaled: the part of the window the frame's 3D view covers (FrameInput::viewRegion within the window).
  VkRect2D viewRectOf(const FrameInput& frame) const;
  bool viewIsWholeWindow() const;
  Result<void> saveScreenshot(const std::filesystem::path& path);
  // The steps of drawFrame after the swapchain image is acquired.
  Result<void> ensureScreenshotBuffer(VkExtent2D extent);
  // The frame's commands: shadow pass, the 3D view (and overlay), the blit when scaled, the screenshot copy.
  Result<void> recordFrame(const FrameSync& f, uint32_t slot, uint32_t image, const FrameInput& frame, bool reuseView);
  // Swapchain image -> screenshotBuffer_, back to present layout, visible to the host.
  void recordScreenshotCopy(VkCommandBuffer cmd, uint32_t image) const;
  // Submits the frame (signalling f's fence) and presents it, or leaves it to the next drawFrame
  // (deferPresent_); a stale swapchain is marked, not an error.
  Result<void> submitAndPresent(const FrameSync& f, uint32_t image, StepClock& clock);
  // Presents swapchain image `image` (its render-finished semaphore signalled by the frame's submit).
  Result<void> present(uint32_t image);
  // The layout a finished frame's image is left in: for the presentation
  // engine, or for the copy into presentBuffers_ when presenter_ puts it.
  VkImageLayout presentLayout() const {
    return presenter_ ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  }
  // presenter_: slot's image -> presentBuffers_[slot], visible to the host.
  void recordPresentCopy(VkCommandBuffer cmd, uint32_t slot) const;
  Result<void> createPresentBuffers(VkExtent2D extent);
  // The frame submitted by the last drawFrame, when its present was deferred.
  Result<void> presentPending();
  // After a presented frame: times it, and on a new scale marks the view for rebuilding.
  void adaptRenderScale();

  const Context* ctx_ = nullptr;
  Window* window_ = nullptr;
  WindowRendererOptions options_;
  std::unique_ptr<SceneLayouts> layouts_;
  std::unique_ptr<ShaderLibrary> shaders_;
  TargetFormat format_;
  UniqueRenderPass renderPass_;   // the 3D view (+ the overlay when not scaled)
  UniqueRenderPass overlayPass_;  // scaled: the overlay over the blitted view
  float renderScale_ = 1.0f;
  VkRect2D viewRect_{};  // the window pixels the 3D view covers (scaled: its images are this size times the scale)
  bool blitView_ = false;
  // Stillness: the content key of the last frame, how many frames in a row
  // had it, and the key the view image holds (while viewValid_).
  uint64_t lastKey_ = 0;
  uint32_t stillFrames_ = 0;
  std::chrono::steady_clock::time_point stillSince_{};
  bool sharpView_ = false;  // adaptive mode, still: the view at full resolution
  uint64_t viewKey_ = 0;
  bool viewValid_ = false;
  bool lastViewReused_ = false;
  std::optional<AdaptiveRenderScale> adaptive_;             // dynamic resolution, when on
  std::chrono::steady_clock::time_point lastPresented_{};  // of the previous presented frame; {}: none to time from
  Swapchain swapchain_;
  bool swapchainStale_ = false;
  // A CPU device's present (Mesa's software WSI) waits in the caller for the
  // frame's rendering and then copies the image to the window: in line, the
  // program's next frame (events, script, graph, UI) could not start until
  // then. So there each frame is presented at the start of the next
  // drawFrame, and the program builds its next frame while this one renders:
  // the picture on screen is one frame later; a GPU presents at once.
  bool deferPresent_ = false;
  std::optional<uint32_t> pendingPresent_;  // the image to present first thing in the next drawFrame
  GpuImage msaaColor_;
  GpuImage depth_;
  GpuImage sceneColor_;                              // scaled: the 3D view before the blit
  UniqueFramebuffer sceneFramebuffer_;               // scaled: the 3D view's
  std::vector<UniqueFramebuffer> framebuffers_;      // per swapchain image (the overlay pass's when scaled)
  std::vector<UniqueSemaphore> renderFinished_;      // per swapchain image
  std::array<FrameSync, kFramesInFlight> frames_;
  SceneRenderer scene_;
  FaultInjector faults_;
  UniqueDescriptorPool imguiPool_;
  Buffer screenshotBuffer_;
  uint32_t frameIndex_ = 0;
  uint32_t lastSlot_ = 0;
  PassTimestamps passTimes_;  // timeFrames: marks between the passes, per slot
  WindowFrameTimes times_;
  std::chrono::steady_clock::time_point lastShaderPoll_{};
  // A CPU device in an X11 window with MIT-SHM (FACIAL_X11_SHM=0 turns it
  // off): frames are rendered into the swapchain's own images, copied into
  // presentBuffers_ and put into the window by presenter_'s thread while the
  // next frame renders (x11_shm_presenter.h); no VkSwapchainKHR.
  std::array<Buffer, kFramesInFlight> presentBuffers_;
  std::unique_ptr<X11ShmPresenter> presenter_;
};

}  // namespace eng::vk
