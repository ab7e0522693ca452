#pragma once
// Headless rendering of model instances to RGBA8 images, and GPU morph
// capture. Everything a CLI command or a test needs besides the Context:
//
//   auto ctx = eng::vk::Context::create({});
//   auto renderer = eng::vk::OffscreenRenderer::create(*ctx, {.width = 512, .height = 512});
//   auto gpuModel = renderer->upload(model);
//   std::vector<float> weights = eng::WeightLayout(model).defaults();
//   eng::vk::ModelInstance instance{&*gpuModel, glm::mat4(1.0f), weights};
//   eng::vk::SceneView view{eng::OrbitCamera::frame(model.bounds())};
//   auto image = renderer->render(view, {&instance, 1});   // eng::Image, RGBA8
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/fault_injection.h"
#include "engine/vk/device/frame_timestamps.h"
#include "engine/vk/device/pass_timestamps.h"
#include "engine/vk/draw/gpu_model.h"
#include "engine/vk/draw/offscreen_target.h"
#include "engine/vk/draw/render_quality.h"
#include "engine/vk/draw/scene_layouts.h"
#include "engine/vk/draw/scene_renderer.h"
#include "engine/vk/draw/scene_view.h"
#include "engine/vk/device/shader_library.h"

namespace eng::vk {

struct OffscreenOptions {
  uint32_t width = 512;
  uint32_t height = 512;
  // Multisampling, shadow map and shading terms (render_quality.h).
  RenderQuality quality = RenderQuality::High;
  // Level of detail (SceneRenderer's LodPolicy) in pixels of the image; 0
  // (renders, goldens) draws every triangle, `facial bench frames --lod-error` sets it.
  float lodPixelError = 0.0f;
  std::filesystem::path shaderSourceDir = defaultShaderSourceDir();  // for reloadChangedShaders()
  // Injected faults for tests (fault_injection.h: device-lost@N counts this
  // renderer's frame submissions); empty: FACIAL_VK_FAULTS, if set.
  std::string faults;
  // Frames submit() may leave in flight (each with its own target and
  // read-back buffer): 2-3 let a sequence read back and encode one frame while
  // the device renders the next. 1 for single images (the memory of one target).
  uint32_t framesInFlight = 1;
};

// Where a collected frame's time went: the CPU waiting for it and copying it
// out, and where the device has timestamps its GPU passes (ms).
struct OffscreenFrameTimes {
  double waitMs = 0.0;      // collect() blocked on the frame's fence
  double readbackMs = 0.0;  // the copy out of the mapped buffer (and un-premultiplying)
  std::optional<double> gpuShadowMs;  // morph pre-pass and shadow map
  std::optional<double> gpuViewMs;    // the 3D view, its resolve and the copy to the read-back buffer
};

class OffscreenRenderer {
 public:
  // `ctx` must outlive the renderer and every model it uploads.
  static Result<OffscreenRenderer> create(const Context& ctx, const OffscreenOptions& options = {});

  Result<GpuModel> upload(const Model& model) const;
  // From a staging of `model` made once for several devices (GpuModelStaging).
  Result<GpuModel> upload(const Model& model, const GpuModelStaging& staging) const;
  Result<eng::Image> render(const SceneView& view, std::span<const ModelInstance> instances);
  // Frames in flight: submit() prepares, records and submits a frame and
  // returns without waiting (the instances' data is copied, so the caller may
  // change it at once); collect() waits for the oldest submitted frame and
  // reads it back. At most framesInFlight() frames are outstanding: submit()
  // then fails until one is collected. render() is submit() and collect()
  // with nothing in flight; the timed and capture calls also need none.
  Result<void> submit(const SceneView& view, std::span<const ModelInstance> instances);
  Result<eng::Image> collect();
  uint32_t framesInFlight() const { return static_cast<uint32_t>(frames_.size()); }
  uint32_t pendingFrames() const { return pending_; }
  // Waits for the frames in flight and drops them (a sequence that failed
  // midway); the destructor does the same.
  void discardPending();
  const OffscreenFrameTimes& lastFrameTimes() const { return lastTimes_; }
  // Times the GPU passes of the frames submitted from now on (where the
  // device has timestamps). Off by default: lavapipe's query read-back waits
  // for the whole device, which would undo the frames in flight.
  void timeGpuPasses(bool on) { timePasses_ = on; }
  // The same frame without the read-back (the image stays on the GPU), for
  // benchmarks: returns once the GPU has finished it, with the GPU time of
  // its command buffer in ms where the device has timestamps (nullopt otherwise).
  Result<std::optional<double>> renderTimed(const SceneView& view, std::span<const ModelInstance> instances);
  bool hasGpuTimestamps() const { return timestamps_.supported(); }
  // Morphed vertices the GPU computes for each (instance, mesh, primitive).
  Result<std::vector<CapturedPrimitive>> capture(std::span<const ModelInstance> instances);
  // The morph and capture passes, for benchmarks: every vertex of every
  // instance morphed once by the compute pre-pass, then read (and skinned)
  // by the vertex shader and stored, no rasterisation, nothing read back; the
  // GPU time in ms where the device has timestamps. Needs canCapture().
  Result<std::optional<double>> captureTimed(std::span<const ModelInstance> instances);
  // The morph pre-pass alone, as every frame runs it once (benchmarks); the
  // GPU time in ms where the device has timestamps.
  Result<std::optional<double>> morphTimed(std::span<const ModelInstance> instances);

  FrameStats lastFrameStats() const { return scene_.stats(0); }
  // Recompiles the shaders if their sources changed and rebuilds the
  // pipelines; on a compile error logs it and keeps drawing with the old ones.
  bool reloadChangedShaders();

  VkExtent2D extent() const { return target().extent(); }
  VkSampleCountFlagBits samples() const { return target().format().samples; }
  RenderQuality quality() const { return scene_.quality(); }
  bool canCapture() const { return scene_.canCapture(); }

  OffscreenRenderer() = default;
  OffscreenRenderer(OffscreenRenderer&&) = default;
  OffscreenRenderer& operator=(OffscreenRenderer&&) = default;
  ~OffscreenRenderer() { discardPending(); }

 private:
  // One frame slot: its own target (and read-back buffer), command buffer
  // and fence; the scene renderer's slot of the same index holds its data.
  struct Frame {
    OffscreenTarget target;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // from pool_
    UniqueFence done;
    bool transparent = false;  // its backdrop: un-premultiplied when read back
    bool timed = false;        // its passes were timed (timeGpuPasses)
  };
  static constexpr uint32_t kPassMarks = 3;  // start, after the shadow pass, end

  const OffscreenTarget& target() const { return frames_.front().target; }
  Result<void> createFrames(uint32_t count, const OffscreenOptions& options);
  // An error while frames are in flight (the one-submission calls share slot 0).
  Result<void> requireIdle(const char* call) const;
  Result<void> recordFrame(Frame& frame, uint32_t slot, const SceneView& view);

  // A frame's submission result, then the fault a test injects; a lost
  // device, real or injected, said plainly (explainDeviceLost).
  Result<void> frameSubmitted(Result<void> submitted);

  const Context* ctx_ = nullptr;
  // Heap-held: the scene renderer and uploaded models point at them.
  std::unique_ptr<SceneLayouts> layouts_;
  std::unique_ptr<ShaderLibrary> shaders_;
  UniqueCommandPool pool_;
  std::vector<Frame> frames_;  // [0] also serves the one-submission calls
  uint32_t next_ = 0;     // the slot submit() fills next
  uint32_t pending_ = 0;  // submitted, not collected: the slots before next_
  OffscreenFrameTimes lastTimes_;
  bool timePasses_ = false;
  SceneRenderer scene_;
  FrameTimestamps timestamps_;
  PassTimestamps passTimes_;
  FaultInjector faults_;
  float lodPixelError_ = 0.0f;
};

}  // namespace eng::vk
