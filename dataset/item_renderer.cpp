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

ItemRenderer::ItemRenderer(const DatasetSpec& spec, app::FaceSetup face, app::SequenceRenderers renderers)
    : spec_(&spec),
      face_(std::make_unique<app::FaceSetup>(std::move(face))),
      renderers_(std::move(renderers)) {}

eng::Result<ItemRenderer> ItemRenderer::create(const DatasetSpec& spec, uint32_t model, const ItemRendererOptions& options) {
  if (options.framesInFlight == 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "a dataset renderer needs at least one frame in flight");
  const std::filesystem::path file = modelFile(spec, model);
  auto quality = app::qualityOption(spec.quality);
  if (!quality) return quality.error();
  // The devices open while the face loads.
  auto opening = app::SequenceRenderers::open(
      {.width = spec.width, .height = spec.height, .device = options.device, .quality = *quality,
       .framesInFlight = options.framesInFlight},
      options.lanes);
  auto face = app::FaceSetup::load({.model = file, .program = "facial dataset"});
  if (!face) return face.error();
  auto renderers = opening.finish(face->displayModel());
  if (!renderers) return renderers.error();
  ItemRenderer r(spec, std::move(*face), std::move(*renderers));
  auto materials = app::FaceMaterials::create(*r.face_);
  if (!materials) return materials.error();
  r.materials_.emplace(std::move(*materials));
  auto rest = restLandmarks(*r.face_, file.empty(), options.device);
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
  eng::vk::SceneView& view = renderers_.view();
  view.camera.yawDegrees = item.yaw;
  view.camera.pitchDegrees = item.pitch;
  view.camera.zoom = item.zoom;
  view.lights = findLightRig(spec_->lights[item.light])->rig;
  view.backdrop = *app::parseBackground(spec_->backgrounds[item.background]);  // checked with the spec
}

ItemLabel ItemRenderer::label(const ItemParams& item) const {
  ItemLabel label;
  label.index = item.index;
  label.image = imageName(item.index, spec_->count);
  label.model = modelLabel(*spec_, item.model);
  label.emotion = spec_->emotions[item.emotion];
  label.intensity = item.intensity;
  for (size_t c = 0; c < auWeights_.size(); ++c)
    if (auWeights_[c] != 0.0f) label.actionUnits.emplace_back(std::string(facial::actionUnits()[c].name), auWeights_[c]);
  for (size_t t = 0; t < weights_.size(); ++t)
    if (weights_[t] != 0.0f) label.targets.emplace_back(targetNames_[t], weights_[t]);
  const eng::OrbitCamera& camera = renderers_.view().camera;
  label.landmarks = projectLandmarks(world_, camera, spec_->width, spec_->height);
  label.light = spec_->lights[item.light];
  label.background = spec_->backgrounds[item.background];
  label.camera = camera;
  label.width = spec_->width, label.height = spec_->height;
  return label;
}

eng::Result<void> ItemRenderer::submit(const ItemParams& item) {
  if (full())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "item " + std::to_string(item.index) + ": " +
                                                               std::to_string(labels_.size()) +
                                                               " items in flight already: collect one first");
  auto emotion = face_->findExpression(spec_->emotions[item.emotion]);
  if (!emotion) return emotion.error();
  const facial::ExpressionPreset preset = itemPreset(**emotion, item);
  ENG_TRY(face_->expressionWeights(preset, 1.0f, weights_, vrmExpressions_));
  ENG_TRY(facial::ExpressionLibrary::evaluate(preset, 1.0f, auWeights_));
  ENG_TRY(materials_->update(vrmExpressions_));
  ENG_TRY(tracker_->evaluate(weights_, world_));
  placeCamera(item);
  ENG_TRY(renderers_.submit(weights_, materials_->materials()));
  labels_.push_back(label(item));
  return {};
}

eng::Result<RenderedItem> ItemRenderer::collect() {
  if (labels_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no dataset item is in flight");
  ItemLabel oldest = std::move(labels_.front());
  labels_.pop_front();
  auto image = renderers_.collect();
  if (!image) return image.error();
  return RenderedItem{.image = std::move(*image), .label = std::move(oldest)};
}

void ItemRenderer::discardPending() {
  renderers_.discardPending();
  labels_.clear();
}

}  // namespace dataset
