#include "cli/demo/face_override.h"

#include <algorithm>

#include "cli/demo/demo_options.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/json/json_document.h"

namespace cli {

// The pad's graph: the study's 2D control map (ControlMapNode) with four
// presets on the axes around neutral, as labelled on the pad, and blinks on
// top so the face stays alive while it is held.
constexpr const char* kPadGraph = R"({
  "version": 1, "channels": "actionUnits",
  "parameters": [{"name": "padX", "type": "float", "default": 0}, {"name": "padY", "type": "float", "default": 0}],
  "root": {"type": "blink", "input": {"type": "controlMap", "name": "pad",
    "neutral": {"type": "pose", "preset": "neutral"},
    "right": {"type": "pose", "preset": "happy"}, "left": {"type": "pose", "preset": "sad"},
    "up": {"type": "pose", "preset": "surprise"}, "down": {"type": "pose", "preset": "anger"},
    "x": "padX", "y": "padY"}}})";

eng::Result<FaceOverride> FaceOverride::create(app::FaceSetup& setup, const std::filesystem::path& graphPath,
                                               uint64_t seed, bool withPad) {
  FaceOverride o;
  o.setup_ = &setup;
  o.weights_.assign(setup.baseWeights().begin(), setup.baseWeights().end());
  o.expressions_.assign(setup.vrmExpressionCount(), 0.0f);
  if (!withPad) return o;
  auto document = facial::parseJsonText(kPadGraph, "the pad's graph");
  if (!document) return document.error();
  auto graph = facial::parseGraph(*document, graphPath, {.presets = facial::presetLookup(setup.expressions())});
  if (!graph) return graph.error();
  // No idle life: the pad is a pose, the face it is shown on has the life and the gaze.
  auto pad = facial::Character::create(
      {.graph = *graph, .rig = &setup.graphRig(), .restWeights = setup.baseWeights(), .vrm = setup.vrm()},
      setup.layout().names(), {.seed = seed, .idleLife = false});
  if (!pad) return pad.error().prefixed("the pad's graph: ");
  o.padGraph_.emplace(std::move(*pad));
  return o;
}

void FaceOverride::chooseEmotion(int emotion) {
  control_ = Control::Graph;
  if (emotion != 0) chosen_ = emotion;
}

void FaceOverride::setIntensity(float intensity) {
  intensity_ = std::clamp(intensity, 0.0f, 1.0f);
  auto preset = setup_->findExpression(kEmotions[size_t(chosen_)]);
  if (!preset) return;
  control_ = lastOverride_ = Control::Slider;
  // lerp(neutral, preset, intensity): the preset at that intensity over the model's defaults.
  (void)setup_->expressionWeights(**preset, intensity_, weights_, expressions_);
}

void FaceOverride::setPad(glm::vec2 cursor) {
  if (!padGraph_) return;
  pad_ = glm::clamp(cursor, glm::vec2(-1.0f), glm::vec2(1.0f));
  // Both are float parameters of kPadGraph and the cursor is clamped: cannot fail.
  (void)padGraph_->setFloat("padX", pad_.x);
  (void)padGraph_->setFloat("padY", pad_.y);
  control_ = lastOverride_ = Control::Pad;
}

void FaceOverride::update(float dt) {
  const float towards = control_ == Control::Graph ? 0.0f : 1.0f;
  amount_ += std::clamp(towards - amount_, -4.0f * dt, 4.0f * dt);
  if (padGraph_ && (control_ == Control::Pad || (lastOverride_ == Control::Pad && amount_ > 0.0f))) {
    (void)padGraph_->update(dt);  // dt is the loop's clamped frame time
    const std::span<const float> pad = padGraph_->weights();
    std::copy(pad.begin(), pad.end(), weights_.begin());
    const std::span<const float> padExpressions = padGraph_->expressionWeights();
    std::copy(padExpressions.begin(), padExpressions.end(), expressions_.begin());
  }
}

void FaceOverride::applyTo(facial::Character& face) const {
  // Sizes come from the same face set-up and the amount stays in [0, 1]: cannot fail.
  (void)face.overridePose(weights_, expressions_, amount_);
}

}  // namespace cli
