#include "demo/face_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "engine/scene/gltf_loader.h"
#include "facial/runtime/rig/action_units.h"

namespace cli {

std::filesystem::path dataDirectory() {
  if (const char* dir = std::getenv("FACIAL_DATA_DIR"); dir && *dir) return dir;
  return std::filesystem::path(FACIAL_SOURCE_DIR) / "data";
}

std::filesystem::path defaultModelPath() { return dataDirectory() / "head.glb"; }

std::filesystem::path defaultExpressionsPath() { return dataDirectory() / "expressions.json"; }

std::string modelNameOf(const std::filesystem::path& modelPath) { return modelPath.stem().string(); }

eng::Result<facial::RigMapping> buildModelRig(const eng::Model& model, const std::filesystem::path& rigmapFile) {
  const std::vector<std::string> targetNames = eng::WeightLayout(model).names();
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(model.sourcePath);
  options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  auto rig = facial::buildRigMapping(targetNames, options);
  if (!rig) return eng::makeError(model.sourcePath + ": " + rig.error().message);
  return rig;
}

eng::Result<FaceSetup> FaceSetup::load(const FaceSetupOptions& options) {
  const std::filesystem::path modelPath = options.model.empty() ? defaultModelPath() : options.model;
  auto model = eng::loadModel(modelPath);
  if (!model) return model.error();
  auto rig = buildModelRig(*model, options.rigmap);
  if (!rig) return rig.error();
  auto expressions =
      facial::ExpressionLibrary::load(options.expressions.empty() ? defaultExpressionsPath() : options.expressions);
  if (!expressions) return expressions.error();
  return FaceSetup(std::move(*model), modelNameOf(modelPath), std::move(*rig), std::move(*expressions));
}

FaceSetup::FaceSetup(eng::Model model, std::string name, facial::RigMapping rig, facial::ExpressionLibrary expressions)
    : model_(std::move(model)),
      name_(std::move(name)),
      layout_(model_),
      rig_(std::move(rig)),
      expressions_(std::move(expressions)),
      baseWeights_(layout_.defaults()),
      actionUnitScratch_(facial::actionUnits().size(), 0.0f),
      emotionScratch_(facial::kEmotionCount, 0.0f) {}

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
