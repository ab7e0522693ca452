#pragma once
// Everything a command needs to pose a face with the project's expressions:
// the face (importers::loadFace: glTF / GLB, VRM, OBJ keyframe folder or
// CANDIDE-3, told apart by content, dressed for display), its rig mapping
// (data/rigmaps/<model>.json, a VRM's expressions, or the scheme its target
// names follow) and the expression presets (data/expressions.json).
// It turns a preset + intensity into the model's flat weight vector
// (eng::WeightLayout order), allocation-free after load:
//
//   auto face = app::FaceSetup::load({.model = "facecap.glb"});
//   std::vector<float> weights(face->weightCount());
//   auto happy = face->findExpression("happy");
//   face->expressionWeights(**happy, 0.8f, weights);
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/expression_library.h"
#include "engine/view/framing_bounds.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "importers/load_face.h"

namespace CLI {
class App;
}

namespace app {

// Declares the options every command that poses a face shares, with one
// wording: --model/-m (default: the built-in head), --rigmap (a rig map file
// instead of <data>/rigmaps/<model>.json or detection) and --no-autorig (a
// face that cannot show emotions is refused instead of rigged on the fly).
void addFaceOptions(CLI::App& app, std::string& model, std::string& rigmap, bool& noAutorig);
// --shape NAME=VALUE (repeatable): identity parameters (CANDIDE-3 shape units,
// or any morph target) baked into the rest mesh before anything is drawn.
void addShapeOption(CLI::App& app, std::vector<std::string>& shapes);

// The program's data folder: $FACIAL_DATA_DIR when set, else the source tree's data/.
std::filesystem::path dataDirectory();
// <data>/head.glb, the built-in FACS head.
std::filesystem::path defaultModelPath();
// <data>/expressions.json.
std::filesystem::path defaultExpressionsPath();

// A model's name for titles and rig map look-up: the file name without extension.
std::string modelNameOf(const std::filesystem::path& modelPath);

// Where a face's rig map may come from: the one given, or else also the
// shipped one named after the face (<data>/rigmaps/<model name>.json). A face
// rigged on the fly looks for the given one only: a map found by its name was
// written for another face of that name (the built-in head's head.json and a
// scan called head.stl).
enum class RigMapLookup : uint8_t { GivenOrByName, GivenOnly };

// The rig mapping of a loaded model over its flat target names: `rigmapFile`
// when given, else <data>/rigmaps/<model name>.json when it exists (and
// `lookup` allows), else the detected scheme; its action-unit strengths
// calibrated to the model (facial/runtime/rig/rig_calibration.h). Errors
// start with the model file.
eng::Result<facial::RigCalibration> buildModelRig(const eng::Model& model, const std::filesystem::path& rigmapFile = {},
                                                  RigMapLookup lookup = RigMapLookup::GivenOrByName);
// Per flat target: the largest world-space displacement at weight 1, divided
// by the height of the region the targets move (the face).
std::vector<float> targetReach(const eng::Model& model);
// The rig of a loaded face: a VRM's is detected over its expressions and
// carried to the morph targets by their binds (facial::buildVrmRigMapping),
// uncalibrated (its expressions are whole poses the author tuned); any other
// face's as buildModelRig.
eng::Result<facial::RigCalibration> buildFaceRig(const importers::LoadedFace& face, const std::filesystem::path& rigmapFile = {},
                                                 RigMapLookup lookup = RigMapLookup::GivenOrByName);

struct FaceSetupOptions {
  std::filesystem::path model;        // empty: defaultModelPath()
  std::filesystem::path expressions;  // empty: defaultExpressionsPath()
  std::filesystem::path rigmap;       // empty: look-up / detection (buildModelRig)
  std::vector<std::string> shapes;    // "NAME=VALUE" identity parameters (importers::bakeShapes)
  // The programs draw faces dressed (importers/face_dressing.h); a caller
  // that dresses what it draws itself (the editor's sculpted model) turns it off.
  bool dressForDisplay = true;
  // A glTF face that cannot show emotions (app::autorigReason: no scheme knows
  // its targets, or visemes only) is given the built-in head's action units
  // first (app::autorigCached), with one note on stderr naming `program`;
  // false refuses it with one error line instead. A face that shows emotions
  // in part (brows or lip corners: app::emotesInPart) is never refused: with
  // false, or when autorig fails (with a warning), it keeps its own rig.
  bool autorig = true;
  std::string_view program = "facial";
};

class FaceSetup {
 public:
  // Errors name the file that failed (model, rig map or presets).
  static eng::Result<FaceSetup> load(const FaceSetupOptions& options = {});

  // The face as loaded (shapes baked): what the rig, the framing and CPU
  // posing read, and what is exported.
  const eng::Model& model() const { return model_; }
  // What to upload for drawing: the model dressed for display when it needed
  // dressing (importers::LoadedFace::displayModel), else model().
  const eng::Model& displayModel() const { return dressed_ ? *dressed_ : model_; }
  importers::FaceFormat format() const { return format_; }
  // The VRM expressions (null unless format() is Vrm).
  const facial::VrmExpressionSet* vrm() const { return vrm_.get(); }
  const std::string& name() const { return name_; }
  // The note printed when the face was rigged on the fly (or the warning when
  // a face that shows emotions in part could not be: app::emotesInPart), else "".
  const std::string& autorigNote() const { return autorigNote_; }
  const eng::WeightLayout& layout() const { return layout_; }
  const facial::RigMapping& rig() const { return rig_; }
  // The rig as a graph that speaks action units sees it (FaceDriver): the
  // same rows, plus every emotion-level binding ("happy" -> a whole-expression
  // target) re-expressed over action units (facial/runtime/rig/action_unit_rig.h). Equal to
  // rig() when the rig binds no emotion.
  const facial::RigMapping& graphRig() const { return graphRig_; }
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
  // (clamped to [0, 1]). vrmExpressions, when not empty (vrmExpressionCount()
  // long), receives the rig's expression weights for the VRM material binds
  // (FaceMaterials::update). Errors (nothing written): non-finite intensity,
  // wrong sizes.
  eng::Result<void> expressionWeights(const facial::ExpressionPreset& preset, float intensity,
                                      std::span<float> weights, std::span<float> vrmExpressions = {});
  // Expressions of the rig's expression stage (a VRM face), else 0.
  uint32_t vrmExpressionCount() const {
    return rig_.expressionStage() ? static_cast<uint32_t>(rig_.controlNames().size()) : 0u;
  }

 private:
  FaceSetup(importers::LoadedFace face, std::string name, facial::RigMapping rig, facial::RigMapping graphRig,
            facial::ExpressionLibrary expressions);

  eng::Model model_;
  std::optional<eng::Model> dressed_;
  importers::FaceFormat format_ = importers::FaceFormat::Gltf;
  std::shared_ptr<const facial::VrmExpressionSet> vrm_;
  std::string name_;
  std::string autorigNote_;
  eng::WeightLayout layout_;
  facial::RigMapping rig_;
  facial::RigMapping graphRig_;
  facial::ExpressionLibrary expressions_;
  std::vector<float> baseWeights_;
  // Scratch reused by expressionWeights (no allocation per call).
  std::vector<float> actionUnitScratch_;
  std::vector<float> emotionScratch_;
};

}  // namespace app
