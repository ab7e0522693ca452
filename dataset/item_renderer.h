#pragma once
// Renders dataset items of ONE model: the face with its rig and presets
// (app::FaceSetup), headless renderers whose camera, lights and backdrop
// change per item, and the landmark tracker that follows the 68 points onto
// the posed mesh. The item's label is made from the same weights and camera
// the image was drawn with.
//
// Items go through frames in flight, like a video's frames (app::recordSequence):
// submit() poses, labels and submits an item to the next lane (on a CPU
// rasteriser two devices take turns, app::SequenceRenderers), collect() reads
// back the oldest. The caller encodes and writes one item while the devices
// draw the next ones.
//
//   while (more) {
//     if (renderer.full()) write(renderer.collect());
//     renderer.submit(next);
//   }
//   while (renderer.pending() > 0) write(renderer.collect());
#include <cstdint>
#include <deque>
#include <string>
#include <memory>
#include <optional>
#include <vector>

#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "dataset/dataset_spec.h"
#include "dataset/item_label.h"
#include "dataset/item_params.h"
#include "dataset/landmark_tracker.h"
#include "engine/scene/model.h"

namespace dataset {

struct RenderedItem {
  eng::Image image;
  ItemLabel label;
};

struct ItemRendererOptions {
  std::string device;  // eng::vk::ContextOptions::device
  // Devices taking turns (app::SequenceRenderers::open); 0: 2 on a CPU
  // rasteriser with 2 or more cores to run on, else 1.
  uint32_t lanes = 0;
  uint32_t framesInFlight = app::kSequenceFramesInFlight;  // per lane
};

class ItemRenderer {
 public:
  // Loads spec.models[model] and finds its rest landmarks (the built-in
  // head's own layout; dlib on a front view for any other face). Errors name
  // the model file.
  static eng::Result<ItemRenderer> create(const DatasetSpec& spec, uint32_t model, const ItemRendererOptions& options);

  // Poses, labels and submits `item` (of this renderer's model). Refused when
  // full(): collect() first.
  eng::Result<void> submit(const ItemParams& item);
  // The oldest submitted item, drawn and labelled. Refused when none is pending.
  eng::Result<RenderedItem> collect();
  size_t pending() const { return labels_.size(); }
  // The next submit() would be refused.
  bool full() const { return renderers_.full(); }
  // Drops the items in flight (after an error: nothing of them is kept).
  void discardPending();

  eng::Result<void> checkValidation() const { return renderers_.checkValidation(); }
  const std::string& deviceName() const { return renderers_.deviceName(); }
  uint32_t laneCount() const { return renderers_.laneCount(); }

 private:
  ItemRenderer(const DatasetSpec& spec, app::FaceSetup face, app::SequenceRenderers renderers);
  void placeCamera(const ItemParams& item);
  ItemLabel label(const ItemParams& item) const;

  const DatasetSpec* spec_;
  std::unique_ptr<app::FaceSetup> face_;  // stable address: the tracker points into its model
  app::SequenceRenderers renderers_;
  std::deque<ItemLabel> labels_;  // of the items in flight, oldest first
  std::optional<app::FaceMaterials> materials_;
  std::optional<LandmarkTracker> tracker_;
  std::vector<std::string> targetNames_;  // the model's, flat
  std::vector<float> weights_, vrmExpressions_, auWeights_;
  Landmarks3 world_{};
};

}  // namespace dataset
