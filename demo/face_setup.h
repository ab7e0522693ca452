#pragma once
// Everything a command needs to pose a face with the project's expressions:
// the model, its rig mapping (data/rigmaps/<model>.json or the scheme its
// target names follow) and the expression presets (data/expressions.json).
// It turns a preset + intensity into the model's flat weight vector
// (eng::WeightLayout order), allocation-free after load:
//
//   auto face = cli::FaceSetup::load({.model = "facecap.glb"});
//   std::vector<float> weights(face->weightCount());
//   auto happy = face->findExpression("happy");
//   face->expressionWeights(**happy, 0.8f, weights);
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace cli {

// The program's data folder: $FACIAL_DATA_DIR when set, else the source tree's data/.
std::filesystem::path dataDirectory();
// <data>/head.glb, the built-in FACS head.
std::filesystem::path defaultModelPath();
// <data>/expressions.json.
std::filesystem::path defaultExpressionsPath();

// A model's name for titles and rig map look-up: the file name without extension.
std::string modelNameOf(const std::filesystem::path& modelPath);

// The rig mapping of a loaded model over its flat target names: `rigmapFile`
// when given, else <data>/rigmaps/<model name>.json when it exists, else the
// detected scheme. Errors start with the model file.
eng::Result<facial::RigMapping> buildModelRig(const eng::Model& model, const std::filesystem::path& rigmapFile = {});

struct FaceSetupOptions {
  std::filesystem::path model;        // empty: defaultModelPath()
  std::filesystem::path expressions;  // empty: defaultExpressionsPath()
  std::filesystem::path rigmap;       // empty: look-up / detection (buildModelRig)
};

class FaceSetup {
 public:
  // Errors name the file that failed (model, rig map or presets).
  static eng::Result<FaceSetup> load(const FaceSetupOptions& options = {});

  const eng::Model& model() const { return model_; }
  const std::string& name() const { return name_; }
  const eng::WeightLayout& layout() const { return layout_; }
  const facial::RigMapping& rig() const { return rig_; }
  const facial::ExpressionLibrary& expressions() const { return expressions_; }
  uint32_t weightCount() const { return layout_.total(); }
  // The model's default weights: the base every expression starts from.
  std::span<const float> baseWeights() const { return baseWeights_; }

  // The preset called `name`, or an error listing the available names.
  eng::Result<const facial::ExpressionPreset*> findExpression(std::string_view name) const;
  // The presets of one kind (basic or compound), in file order.
  std::vector<const facial::ExpressionPreset*> presets(bool compound) const;

  // weights = the model's defaults, then every target the rig drives
  // overwritten with the preset's action units and emotions at `intensity`
  // (clamped to [0, 1]). Errors (nothing written): non-finite intensity,
  // weights.size() != weightCount().
  eng::Result<void> expressionWeights(const facial::ExpressionPreset& preset, float intensity,
                                      std::span<float> weights);

 private:
  FaceSetup(eng::Model model, std::string name, facial::RigMapping rig, facial::ExpressionLibrary expressions);

  eng::Model model_;
  std::string name_;
  eng::WeightLayout layout_;
  facial::RigMapping rig_;
  facial::ExpressionLibrary expressions_;
  std::vector<float> baseWeights_;
  // Scratch reused by expressionWeights (no allocation per call).
  std::vector<float> actionUnitScratch_;
  std::vector<float> emotionScratch_;
};

}  // namespace cli
