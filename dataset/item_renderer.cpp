#include "dataset/item_renderer.h"

#include "app/face_landmark_finder.h"
#include "app/view_options.h"
#include "autorig/builtin_source.h"
#include "autorig/posed_face.h"
#include "dataset/light_rigs.h"
#include "engine/view/framing_bounds.h"
#include "facial/runtime/rig/action_units.h"

namespace dataset {
namespace {

// The rest-pose landmarks: the built-in head's fixed layout, or dlib on a
// front view of any other face.
eng::Result<autorig::FaceLandmarks> restLandmarks(const app::FaceSetup& face, bool builtIn, const std::string& device) {
  if (builtIn) {
    auto source = autorig::builtInSource(face.model());
    if (!source) return source.error();
    return source->landmarks;
  }
  const autorig::PosedFace posed = autorig::poseAtRest(face.model());
  return app::findFaceLandmarks(face.model(), posed, {.device = device, .display = &face.displayModel()});
}

}  // namespace

ItemRenderer::ItemRenderer(const DatasetSpec& spec, app::FaceSetup face, app::HeadlessModelRenderer renderer)
    : spec_(&spec), face_(std::make_unique<app::FaceSetup>(std::move(face))), renderer_(std::move(renderer)) {}

eng::Result<ItemRenderer> ItemRenderer::create(const DatasetSpec& spec, uint32_t model, const std::string& device) {
  const std::filesystem::path file = modelFile(spec, model);
  auto face = app::FaceSetup::load({.model = file, .program = "facial dataset"});
  if (!face) return face.error();
  auto quality = app::qualityOption(spec.quality);
  if (!quality) return quality.error();
  auto renderer = app::HeadlessModelRenderer::create(
      face->displayModel(), {.width = spec.width, .height = spec.height, .device = device, .quality = *quality});
  if (!renderer) return renderer.error();
  ItemRenderer r(spec, std::move(*face), std::move(*renderer));
  auto materials = app::FaceMaterials::create(*r.face_);
  if (!materials) return materials.error();
  r.materials_.emplace(std::move(*materials));
  auto rest = restLandmarks(*r.face_, file.empty(), device);
  if (!rest) return rest.error();
  auto tracker = LandmarkTracker::bind(r.face_->model(), *rest);
  if (!tracker) return tracker.error();
  r.tracker_.emplace(std::move(*tracker));
  r.targetNames_ = r.face_->layout().names();
  r.weights_.resize(r.face_->weightCount());
  r.vrmExpressions_.resize(r.face_->vrmExpressionCount());
  r.auWeights_.resize(facial::actionUnits().size());
  return r;
}

void ItemRenderer::placeCamera(const ItemParams& item) {
  eng::vk::SceneView& view = renderer_.view();
  view.camera.yawDegrees = item.yaw;
  view.camera.pitchDegrees = item.pitch;
  view.camera.zoom = item.zoom;
  view.lights = findLightRig(spec_->lights[item.light])->rig;
  view.backdrop = *app::parseBackground(spec_->backgrounds[item.background]);  // checked with the spec
}

eng::Result<RenderedItem> ItemRenderer::render(const ItemParams& item) {
  auto emotion = face_->findExpression(spec_->emotions[item.emotion]);
  if (!emotion) return emotion.error();
  const facial::ExpressionPreset preset = itemPreset(**emotion, item);
  ENG_TRY(face_->expressionWeights(preset, 1.0f, weights_, vrmExpressions_));
  ENG_TRY(facial::ExpressionLibrary::evaluate(preset, 1.0f, auWeights_));
  ENG_TRY(materials_->update(vrmExpressions_));
  placeCamera(item);
  auto image = renderer_.render(weights_, materials_->materials());
  if (!image) return image.error();
  ENG_TRY(tracker_->evaluate(weights_, world_));

  RenderedItem out{.image = std::move(*image), .label = {}};
  ItemLabel& label = out.label;
  label.index = item.index;
  label.image = imageName(item.index, spec_->count);
  label.model = modelLabel(*spec_, item.model);
  label.emotion = spec_->emotions[item.emotion];
  label.intensity = item.intensity;
  for (size_t c = 0; c < auWeights_.size(); ++c)
    if (auWeights_[c] != 0.0f) label.actionUnits.emplace_back(std::string(facial::actionUnits()[c].name), auWeights_[c]);
  for (size_t t = 0; t < weights_.size(); ++t)
    if (weights_[t] != 0.0f) label.targets.emplace_back(targetNames_[t], weights_[t]);
  label.landmarks = projectLandmarks(world_, renderer_.view().camera, spec_->width, spec_->height);
  label.light = spec_->lights[item.light];
  label.background = spec_->backgrounds[item.background];
  label.camera = renderer_.view().camera;
  label.width = spec_->width, label.height = spec_->height;
  return out;
}

}  // namespace dataset
