#pragma once
// The renderers a sequence draws with (app::recordSequence's lanes): one
// model and one camera, options.framesInFlight frames in flight each.
// On a CPU rasteriser a device renders a frame in two halves that do not
// overlap: its queue thread shades vertices and bins triangles, then its
// rasteriser threads fill them (lavapipe kept 2 cores about 80 % busy). A
// second device (a lane) takes every other frame, so one's binning runs while
// the other's rasterising does. On a GPU one lane.
//
// Opening a lane (device, pipelines) does not need the model: open() starts
// it on threads while the caller loads its face, finish() stages the model
// once for every lane (levels of detail, detail runs, sparse deltas) and
// uploads it to each in parallel.
//
//   auto opening = app::SequenceRenderers::open({.width = 512, .height = 512, .framesInFlight = 3});
//   ... load the model ...
//   auto renderers = opening.finish(model);
//   app::recordSequence(renderers->lanes(), options, [&](const app::FrameContext& f) {
//     instance.model = &renderers->gpuModel(f.lane); ... });
#include <cstdint>
#include <memory>
#include <vector>

#include "app/headless_model_renderer.h"
#include "app/sequence_recorder.h"

namespace app {

class SequenceRenderers {
 public:
  // Lanes being opened on threads; finish() waits for them. Dropping it
  // unfinished waits too, and releases them.
  class Opening {
   public:
    eng::Result<SequenceRenderers> finish(const eng::Model& model);

    Opening(Opening&&) noexcept;
    Opening& operator=(Opening&&) noexcept;
    ~Opening();

   private:
    friend class SequenceRenderers;
    struct State;
    explicit Opening(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
  };

  // lanes: how many devices; 0 picks (2 on a CPU rasteriser when the process
  // may run on 2 or more cores, its CPU affinity, else 1).
  static Opening open(const HeadlessRenderOptions& options, uint32_t lanes = 0);
  // open(options, lanes).finish(model).
  static eng::Result<SequenceRenderers> create(const eng::Model& model, const HeadlessRenderOptions& options,
                                               uint32_t lanes = 0);

  // recordSequence's lanes: every renderer with the one view().
  std::vector<SequenceLane> lanes();
  uint32_t laneCount() const { return static_cast<uint32_t>(renderers_.size()); }
  // The model as uploaded to lane `lane`'s device (FrameContext::lane).
  const eng::vk::GpuModel& gpuModel(uint32_t lane) const { return renderers_[lane].gpuModel(); }
  // The camera every lane draws with.
  eng::vk::SceneView& view() { return view_; }
  const std::string& deviceName() const { return renderers_.front().deviceName(); }
  // Every lane's validation messages (HeadlessModelRenderer::checkValidation).
  eng::Result<void> checkValidation() const;

 private:
  std::vector<HeadlessModelRenderer> renderers_;
  eng::vk::SceneView view_;
};

}  // namespace app
