#pragma once
// One model rendered headless many times with different weights from one
// fixed camera: ONE Vulkan context, offscreen target and GPU upload shared by
// every frame (a contact sheet of expressions re-creates nothing per tile).
// The camera frames eng::framingBounds, so it stays put across weights.
//
//   auto renderer = app::HeadlessModelRenderer::create(model, {.width = 256, .height = 256});
//   auto image = renderer->render(weights);
//   if (auto clean = renderer->checkValidation(); !clean) ...  // FACIAL_VALIDATION=1 runs
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/vk/device/context.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/gpu_model.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "engine/vk/draw/scene_view.h"

namespace app {

struct HeadlessRenderOptions {
  uint32_t width = 512;
  uint32_t height = 512;
  float yawDegrees = 0.0f;    // + = from the face's left
  float pitchDegrees = 0.0f;  // + = from above
  float zoom = 1.0f;          // > 1 = closer
  eng::FramingMode framing = eng::FramingMode::Face;  // head and neck, or the whole model
  std::string device;         // eng::vk::ContextOptions::device
  eng::vk::Backdrop backdrop; // studio gradient, a solid colour or transparent (RGBA for compositing)
  // Multisampling, shadows, shading terms; nullopt: eng::vk::defaultQuality
  // of the device (balanced on a CPU rasteriser, high on a GPU).
  std::optional<eng::vk::RenderQuality> quality;
  float lodPixelError = 0.0f;  // eng::vk::OffscreenOptions::lodPixelError (0: every triangle)
  // eng::vk::OffscreenOptions::framesInFlight: sequences (recordSequence) take
  // app::kSequenceFramesInFlight; single images keep the memory of one target.
  uint32_t framesInFlight = 1;
};

class HeadlessModelRenderer {
 public:
  // `model` is uploaded once; it need not outlive the renderer.
  static eng::Result<HeadlessModelRenderer> create(const eng::Model& model, const HeadlessRenderOptions& options);

  // weights: the model's flat weight vector (eng::WeightLayout order);
  // materials: per-material overrides (FaceMaterials), empty = the model's own.
  eng::Result<eng::Image> render(std::span<const float> weights,
                                 std::span<const eng::vk::InstanceMaterial> materials = {});

  const std::string& deviceName() const { return context_->deviceInfo().name; }

  // For sequences that draw their own instances (eng::vk::ModelInstance with
  // gpuModel()) through recordSequence: the renderer and the camera it uses.
  eng::vk::OffscreenRenderer& offscreen() { return *renderer_; }
  const eng::vk::OffscreenRenderer& offscreen() const { return *renderer_; }
  eng::vk::SceneView& view() { return view_; }
  // Where the model stands in the view (identity: as its file places it);
  // render() draws it there. The landmark finder turns a face lying or
  // looking sideways in its file to the camera this way.
  void place(const glm::mat4& modelToWorld) { placement_ = modelToWorld; }
  const glm::mat4& placement() const { return placement_; }
  const eng::vk::GpuModel& gpuModel() const { return gpuModel_; }
  // An error counting the validation messages reported so far (they were
  // logged as they came), so a validation run fails loudly; ok otherwise.
  eng::Result<void> checkValidation() const;
  VkPhysicalDeviceType deviceType() const { return context_->deviceInfo().type; }

  HeadlessModelRenderer(HeadlessModelRenderer&&) noexcept = default;
  HeadlessModelRenderer& operator=(HeadlessModelRenderer&&) = delete;  // member-wise, it would free the context first
  // Frames still in flight (offscreen().submit() without collect(), e.g. a
  // caller returning on an error) are dropped before the model they draw is freed.
  ~HeadlessModelRenderer() {
    if (renderer_) renderer_->discardPending();
  }

 private:
  HeadlessModelRenderer() = default;
  // SequenceRenderers opens its lanes (device, pipelines) while the caller
  // loads the model, then shows the model staged once on each.
  friend class SequenceRenderers;
  static eng::Result<std::unique_ptr<eng::vk::Context>> createContext(const HeadlessRenderOptions& options,
                                                                      bool announce = true);
  // The renderer on `context`, no model yet.
  static eng::Result<HeadlessModelRenderer> open(const HeadlessRenderOptions& options,
                                                 std::unique_ptr<eng::vk::Context> context);
  // Uploads `model` (staging: null to stage it for this device alone) and frames it.
  eng::Result<void> show(const eng::Model& model, const HeadlessRenderOptions& options,
                         const eng::vk::GpuModelStaging* staging);

  // Declared in creation order: destroyed model first, context last.
  std::unique_ptr<eng::vk::Context> context_;  // stable address: the renderer points at it
  std::unique_ptr<eng::vk::OffscreenRenderer> renderer_;
  eng::vk::GpuModel gpuModel_;
  eng::vk::SceneView view_;
  glm::mat4 placement_{1.0f};
  std::string modelName_;
};

}  // namespace app
