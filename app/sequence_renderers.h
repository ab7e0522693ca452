#pragma once
// The renderers a sequence draws with (app::recordSequence's lanes), and
// pictures drawn in flight without one (a dataset's items, a sheet's tiles,
// a still command's one picture): one model and one camera,
// options.framesInFlight frames in flight each.
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
#include <deque>
#include <memory>
#include <span>
#include <vector>

#include "app/headless_model_renderer.h"
#include "app/sequence_recorder.h"

namespace app {

// The cores this process may run on (its CPU affinity: a Slurm task's, a
// container's), not the machine's.
unsigned usableCores();

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

  // Pictures of the model in flight without a sequence (a dataset's items, a
  // contact sheet's tiles): submit() draws it with `weights` and `materials`
  // (HeadlessModelRenderer::render's) from view() as they are now, on the next
  // lane in turn, and may be followed at once by changes to all three;
  // collect() reads back the oldest. Refused when full() / nothing is pending.
  eng::Result<void> submit(std::span<const float> weights, std::span<const eng::vk::InstanceMaterial> materials = {});
  eng::Result<eng::Image> collect();
  bool full() const;
  size_t pending() const { return pending_.size(); }
  // Drops the pictures in flight.
  void discardPending();
  // One picture: submit() then collect() (refused with others in flight).
  // With one lane, a still command opens its device while it loads the face:
  //   auto opening = SequenceRenderers::open(options, 1); ...load...; opening.finish(model)->render(weights);
  eng::Result<eng::Image> render(std::span<const float> weights, std::span<const eng::vk::InstanceMaterial> materials = {});

  uint32_t laneCount() const { return static_cast<uint32_t>(renderers_.size()); }
  // The model as uploaded to lane `lane`'s device (FrameContext::lane).
  const eng::vk::GpuModel& gpuModel(uint32_t lane) const { return renderers_[lane].gpuModel(); }
  // The camera every lane draws with.
  eng::vk::SceneView& view() { return view_; }
  const eng::vk::SceneView& view() const { return view_; }
  const std::string& deviceName() const { return renderers_.front().deviceName(); }
  // Every lane's validation messages (HeadlessModelRenderer::checkValidation).
  eng::Result<void> checkValidation() const;

 private:
  std::vector<HeadlessModelRenderer> renderers_;
  eng::vk::SceneView view_;
  std::deque<uint32_t> pending_;  // the lane of each submitted picture, oldest first
  uint32_t nextLane_ = 0;
};

}  // namespace app
