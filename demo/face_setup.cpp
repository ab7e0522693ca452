#include "demo/face_setup.h"

#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <CLI/CLI.hpp>
#include <Eigen/Dense>

#include "engine/scene/gltf_loader.h"
#include "facial/runtime/rig/action_units.h"

namespace cli {

void addFaceOptions(CLI::App& app, std::string& model, std::string& rigmap) {
  app.add_option("--model,-m", model, "glTF face (default: the built-in head, <data>/head.glb)");
  app.add_option("--rigmap", rigmap,
                 "Rig map JSON naming which targets are which action unit or emotion "
                 "(default: <data>/rigmaps/<model>.json, else detected from the target names)");
}

std::filesystem::path dataDirectory() {
  if (const char* dir = std::getenv("FACIAL_DATA_DIR"); dir && *dir) return dir;
  return std::filesystem::path(FACIAL_SOURCE_DIR) / "data";
}

std::filesystem::path defaultModelPath() { return dataDirectory() / "head.glb"; }

std::filesystem::path defaultExpressionsPath() { return dataDirectory() / "expressions.json"; }

std::string modelNameOf(const std::filesystem::path& modelPath) { return modelPath.stem().string(); }

std::vector<float> targetReach(const eng::Model& model) {
  const eng::WeightLayout layout(model);
  std::vector<float> reach(layout.total(), 0.0f);
  const eng::Aabb face = eng::vk::morphedRegionBounds(model);
  const float faceSize = face.valid() ? face.size().y : 0.0f;
  if (!(faceSize > 0.0f)) return reach;
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const int m = model.nodes[i].mesh;
    if (m < 0 || size_t(m) >= model.meshes.size()) continue;
    const glm::mat3 linear(model.worldTransform(int(i)));
    const eng::Mesh& mesh = model.meshes[size_t(m)];
    for (const eng::Primitive& prim : mesh.primitives) {
      for (size_t t = 0; t < prim.targets.size() && t < layout.count(m); ++t) {
        float& r = reach[layout.offset(m) + t];
        for (const glm::vec3& d : prim.targets[t].positions) r = std::max(r, glm::length(linear * d) / faceSize);
      }
    }
  }
  return reach;
}

eng::Result<facial::RigCalibration> buildModelRig(const eng::Model& model, const std::filesystem::path& rigmapFile) {
  const std::vector<std::string> targetNames = eng::WeightLayout(model).names();
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(model.sourcePath);
  options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  auto rig = facial::buildRigMapping(targetNames, options);
  if (!rig) return eng::makeError(model.sourcePath + ": " + rig.error().message);
  facial::RigCalibrationOptions calibration;
  if (const std::filesystem::path file = facial::rigMapFileFor(options); !file.empty()) {
    auto rigmap = facial::loadRigMapFile(file, targetNames);
    if (!rigmap) return eng::makeError(model.sourcePath + ": " + rigmap.error().message);
    calibration.overrides = std::move(rigmap->calibration);
  }
  auto calibrated = facial::calibrateRig(*rig, targetReach(model), calibration);
  if (!calibrated) return eng::makeError(model.sourcePath + ": " + calibrated.error().message);
  return calibrated;
}

eng::Result<facial::RigMapping> actionUnitRig(const facial::RigMapping& rig, const facial::ExpressionLibrary& presets) {
  const uint32_t auCount = static_cast<uint32_t>(facial::actionUnits().size());
  const std::span<const std::string_view> emotions = facial::emotionNames();
  bool bindsEmotions = false;
  for (uint32_t e = 0; e < emotions.size(); ++e)
    bindsEmotions |= !rig.targets(facial::emotionInput(facial::Emotion(e))).empty();
  if (!bindsEmotions) return rig;

  // P: one column per basic emotion (neutral excluded), its preset at intensity 1.
  constexpr uint32_t kBasic = facial::kEmotionCount - 1;
  Eigen::MatrixXd pattern = Eigen::MatrixXd::Zero(auCount, kBasic);
  std::vector<float> au(auCount);
  for (uint32_t k = 0; k < kBasic; ++k) {
    const std::string_view name = emotions[k + 1];
    const facial::ExpressionPreset* preset = presets.find(name);
    if (!preset || preset->isCompound())
      return eng::makeError("the rig binds emotions, so the graph's action units are decoded through the basic "
                            "presets, but the presets have no basic '" + std::string(name) + "'");
    if (auto r = facial::ExpressionLibrary::evaluate(*preset, 1.0f, au); !r) return r.error();
    for (uint32_t a = 0; a < auCount; ++a) pattern(a, k) = au[a];
  }
  const Eigen::MatrixXd gram = pattern.transpose() * pattern;
  const Eigen::LDLT<Eigen::MatrixXd> solver(gram);
  // Relative to the largest pivot: a preset that is (nearly) a mix of the others cannot be told apart.
  const Eigen::VectorXd pivots = solver.vectorD().cwiseAbs();
  if (solver.info() != Eigen::Success || pivots.minCoeff() <= 1e-9 * pivots.maxCoeff())
    return eng::makeError("the basic presets' action units are linearly dependent; emotion-level rig bindings "
                          "cannot be decoded from the graph's action units");
  const Eigen::MatrixXd decode = solver.solve(pattern.transpose());  // kBasic x auCount

  facial::RigMappingBuilder builder(rig.scheme(), rig.targetNames());
  builder.setDetail(rig.report().detail);
  for (const std::string& note : rig.report().notes) builder.note(note);
  builder.setWeightRange(rig.minWeight(), rig.maxWeight());
  for (uint32_t input = 0; input < facial::rigInputCount(); ++input) {
    const auto targets = rig.targets(input);
    const auto gains = rig.gains(input);
    for (size_t i = 0; i < targets.size(); ++i) builder.add(input, targets[i], gains[i]);
  }
  for (uint32_t k = 0; k < kBasic; ++k) {
    const uint32_t emotion = facial::emotionInput(facial::Emotion(k + 1));
    const auto targets = rig.targets(emotion);
    const auto gains = rig.gains(emotion);
    for (uint32_t a = 0; a < auCount; ++a) {
      const double d = decode(k, a);
      if (std::abs(d) < 1e-6) continue;
      for (size_t i = 0; i < targets.size(); ++i) builder.add(a, targets[i], static_cast<float>(d * gains[i]));
    }
  }
  if (!rig.targets(facial::emotionInput(facial::Emotion::Neutral)).empty())
    builder.note("neutral: a target bound to the neutral emotion is not driven by action-unit graphs "
                 "(neutral has no action units to decode)");
  builder.note("emotion bindings are driven from the action units through the basic presets (least squares)");
  return builder.build();
}

eng::Result<FaceSetup> FaceSetup::load(const FaceSetupOptions& options) {
  const std::filesystem::path modelPath = options.model.empty() ? defaultModelPath() : options.model;
  auto model = eng::loadModel(modelPath);
  if (!model) return model.error();
  auto calibration = buildModelRig(*model, options.rigmap);
  if (!calibration) return calibration.error();
  auto rig = std::optional<facial::RigMapping>(std::move(calibration->rig));
  auto expressions =
      facial::ExpressionLibrary::load(options.expressions.empty() ? defaultExpressionsPath() : options.expressions);
  if (!expressions) return expressions.error();
  auto graphRig = actionUnitRig(*rig, *expressions);
  if (!graphRig) return eng::makeError(modelPath.string() + ": " + graphRig.error().message);
  return FaceSetup(std::move(*model), modelNameOf(modelPath), std::move(*rig), std::move(*graphRig),
                   std::move(*expressions));
}

FaceSetup::FaceSetup(eng::Model model, std::string name, facial::RigMapping rig, facial::RigMapping graphRig,
                     facial::ExpressionLibrary expressions)
    : model_(std::move(model)),
      name_(std::move(name)),
      layout_(model_),
      rig_(std::move(rig)),
      graphRig_(std::move(graphRig)),
      expressions_(std::move(expressions)),
      baseWeights_(layout_.defaults()),
      actionUnitScratch_(facial::actionUnits().size(), 0.0f),
      emotionScratch_(facial::kEmotionCount, 0.0f) {
  // ARKit's 52 shapes are all expression (none is identity), so the neutral
  // face has every one at 0. A file's default weights on them are a captured
  // frame (facecap's look down, press the lips and sneer a little), not the
  // face at rest; other targets (identity, body shapes) keep their defaults.
  if (rig_.scheme() == facial::RigScheme::Arkit52) {
    const std::vector<std::string> names = layout_.names();
    for (size_t i = 0; i < names.size(); ++i)
      if (facial::arkitIndex(names[i])) baseWeights_[i] = 0.0f;
  }
}

eng::Result<const facial::ExpressionPreset*> FaceSetup::findExpression(std::string_view name) const {
  if (const facial::ExpressionPreset* preset = expressions_.find(name)) return preset;
  std::string available;
  for (std::string_view n : expressions_.names()) available += (available.empty() ? "" : ", ") + std::string(n);
  return eng::makeError("unknown expression '" + std::string(name) + "'; available: " + available);
}

std::vector<const facial::ExpressionPreset*> FaceSetup::presets(bool compound) const {
  std::vector<const facial::ExpressionPreset*> picked;
  for (const facial::ExpressionPreset& preset : expressions_.presets())
    if (preset.isCompound() == compound) picked.push_back(&preset);
  return picked;
}

eng::Result<void> FaceSetup::expressionWeights(const facial::ExpressionPreset& preset, float intensity,
                                               std::span<float> weights) {
  if (!std::isfinite(intensity))
    return eng::makeError("expression '" + preset.name + "': intensity " + std::to_string(intensity) +
                          " is not a finite number");
  if (weights.size() != weightCount())
    return eng::makeError("expression '" + preset.name + "': " + std::to_string(weights.size()) +
                          " weights given, " + name_ + " has " + std::to_string(weightCount()));
  const float clamped = std::clamp(intensity, 0.0f, 1.0f);
  if (auto au = facial::ExpressionLibrary::evaluate(preset, clamped, actionUnitScratch_); !au) return au.error();
  if (auto em = facial::ExpressionLibrary::evaluateEmotions(preset, clamped, emotionScratch_); !em) return em.error();
  std::copy(baseWeights_.begin(), baseWeights_.end(), weights.begin());
  return rig_.apply(actionUnitScratch_, emotionScratch_, weights);
}

}  // namespace cli
