#pragma once
// Renders dataset items of ONE model: the face with its rig and presets
// (app::FaceSetup), one headless renderer whose camera, lights and backdrop
// change per item, and the landmark tracker that follows the 68 points onto
// the posed mesh. The item's label is made from the same weights and camera
// the image was drawn with.
#include <string>
#include <memory>
#include <optional>
#include <vector>

#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/headless_model_renderer.h"
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

class ItemRenderer {
 public:
  // Loads spec.models[model] and finds its rest landmarks (the built-in
  // head's own layout; dlib on a front view for any other face). Errors name
  // the model file.
  static eng::Result<ItemRenderer> create(const DatasetSpec& spec, uint32_t model, const std::string& device);

  eng::Result<RenderedItem> render(const ItemParams& item);
  eng::Result<void> checkValidation() const { return renderer_.checkValidation(); }
  const std::string& deviceName() const { return renderer_.deviceName(); }

 private:
  ItemRenderer(const DatasetSpec& spec, app::FaceSetup face, app::HeadlessModelRenderer renderer);
  void placeCamera(const ItemParams& item);

  const DatasetSpec* spec_;
  std::unique_ptr<app::FaceSetup> face_;  // stable address: the tracker points into its model
  app::HeadlessModelRenderer renderer_;
  std::optional<app::FaceMaterials> materials_;
  std::optional<LandmarkTracker> tracker_;
  std::vector<std::string> targetNames_;  // the model's, flat
  std::vector<float> weights_, vrmExpressions_, auWeights_;
  Landmarks3 world_{};
};

}  // namespace dataset
