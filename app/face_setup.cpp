#include "app/face_setup.h"

#include "app/face_autorig.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <CLI/CLI.hpp>

#include "engine/scene/skeleton_pose.h"
#include "facial/runtime/rig/action_unit_rig.h"
#include "facial/runtime/rig/action_units.h"

namespace app {

void addFaceOptions(CLI::App& app, std::string& model, std::string& rigmap, bool& noAutorig) {
  app.add_option("--model,-m", model,
                 std::string(importers::kFaceFormatsHelp) + " (default: the built-in head, <data>/head.glb)");
  app.add_option("--rigmap", rigmap,
                 "Rig map JSON naming which targets are which action unit or emotion "
                 "(default: <data>/rigmaps/<model>.json, else detected from the target names)");
  app.add_flag("--no-autorig", noAutorig,
               "Refuse a face that cannot show emotions (no known targets, or visemes only) instead of giving it "
               "the built-in head's action units on the fly (see `facial autorig`)");
}

void addShapeOption(CLI::App& app, std::vector<std::string>& shapes) {
  app.add_option("--shape", shapes,
                 "Identity parameter NAME=VALUE baked into the face before drawing (repeatable): a CANDIDE-3 "
                 "shape unit (e.g. 'mouth width=0.5', 'SU_Eyes_width=-0.3') or any morph target");
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
  const eng::Aabb face = eng::morphedRegionBounds(model);
  const float faceSize = face.valid() ? face.size().y : 0.0f;
  if (!(faceSize > 0.0f)) return reach;
  const std::vector<glm::mat4> world = eng::restWorldMatrices(model);
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const int m = model.nodes[i].mesh;
    if (m < 0 || size_t(m) >= model.meshes.size()) continue;
    const glm::mat3 linear(world[i]);
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

eng::Result<facial::RigCalibration> buildModelRig(const eng::Model& model, const std::filesystem::path& rigmapFile,
                                                  RigMapLookup lookup) {
  const std::vector<std::string> targetNames = eng::WeightLayout(model).names();
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(model.sourcePath);
  if (lookup == RigMapLookup::GivenOrByName) options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  auto rig = facial::buildRigMapping(targetNames, options);
  if (!rig) return rig.error().prefixed(model.sourcePath + ": ");
  facial::RigCalibrationOptions calibration;
  if (const std::filesystem::path file = facial::rigMapFileFor(options); !file.empty()) {
    auto rigmap = facial::loadRigMapFile(file, targetNames);
    if (!rigmap) return rigmap.error().prefixed(model.sourcePath + ": ");
    // A map found by the face's name that only calibrates was measured on the
    // one file it ships beside (data/rigmaps/head.json: the built-in head's
    // jaw, raised 1.6 times): another face of that name (a scan saved as
    // head.glb with ARKit shapes of its own) is calibrated by its own targets.
    std::error_code ec;
    const bool byName = rigmapFile.empty(), mapsTargets = rigmap->mapping.has_value();
    const bool beside = std::filesystem::equivalent(std::filesystem::path(model.sourcePath).parent_path(), dataDirectory(), ec);
    if (!byName || mapsTargets || beside) calibration.overrides = std::move(rigmap->calibration);
  }
  calibration.given = model.calibration;
  auto calibrated = facial::calibrateRig(*rig, targetReach(model), calibration);
  if (!calibrated) return calibrated.error().prefixed(model.sourcePath + ": ");
  return calibrated;
}

eng::Result<facial::RigCalibration> buildFaceRig(const importers::LoadedFace& face, const std::filesystem::path& rigmapFile,
                                                 RigMapLookup lookup) {
  if (!face.vrm) return buildModelRig(face.model, rigmapFile, lookup);
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(face.model.sourcePath);
  if (lookup == RigMapLookup::GivenOrByName) options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  auto rig = facial::buildVrmRigMapping(face.vrm, eng::WeightLayout(face.model).names(), options);
  if (!rig) return rig.error().prefixed(face.model.sourcePath + ": ");
  return facial::RigCalibration{std::move(*rig), {}};
}

namespace {

// A face that cannot show emotions, rigged on the fly (FaceSetupOptions::autorig):
// the rigged copy from the cache loaded in its place, under its own name. The
// note says so once; errors keep the rig's own message first.
eng::Result<std::string> autorigInPlace(const FaceSetupOptions& options, const std::filesystem::path& modelPath,
                                        const std::string& reason, const eng::Result<facial::RigCalibration>& rig,
                                        eng::Result<importers::LoadedFace>& face) {
  const std::string model = modelPath.string();
  const std::string refusal = cannotEmoteLine(modelPath, reason, rig);
  const bool keepsOwn = keepsOwnRig(*face, rig);  // asked before the rigged copy takes the face's place
  if (!options.autorig)
    return eng::makeError(eng::ErrorKind::Unsupported, refusal + "; --no-autorig refuses to give it the built-in "
                          "head's action units (drop the flag, or write them once with `facial autorig " + model +
                          " --out rigged.glb`)");
  auto cached = loadAutorigged(modelPath, {.shapes = options.shapes, .dressForDisplay = options.dressForDisplay}, *face);
  if (!cached) {
    std::error_code ec;
    const std::filesystem::path beside = landmarksBeside(modelPath);
    return eng::makeError(cached.error().kind, refusal + "; autorig: " + cached.error().message +
                          (std::filesystem::exists(beside, ec) ? "" : " (give its 68 landmarks in " + beside.string() + ")"));
  }
  const std::optional<StandingUp> up = standingUp(cached->landmarks);
  return model + (emotesInPart(rig) ? " shows emotions only in part (" : " cannot show emotions (") + reason +
         "): rigged with the built-in head's action units (" +
         std::to_string(cached->made.size()) + " targets made, its " + std::to_string(cached->kept.size()) +
         " kept), " + (cached->reused ? "from the cache " : "cached as ") + cached->path.string() +
         (keepsOwn ? "; --no-autorig keeps its own rig instead" : "; --no-autorig refuses instead") +
         (up ? "; shown stood up (in its file the face " + up->howItLies + ")" : "");
}

}  // namespace

eng::Result<FaceSetup> FaceSetup::load(const FaceSetupOptions& options) {
  const std::filesystem::path modelPath = options.model.empty() ? defaultModelPath() : options.model;
  auto face = importers::loadFace(modelPath, {.shapes = options.shapes, .dressForDisplay = options.dressForDisplay});
  if (!face) return face.error();
  auto calibration = buildFaceRig(*face, options.rigmap);
  std::string note;
  if (const std::string reason = autorigReason(*face, calibration, options.rigmap); !reason.empty()) {
    const bool inPart = keepsOwnRig(*face, calibration);
    if (options.autorig || !inPart) {
      auto rigged = autorigInPlace(options, modelPath, reason, calibration, face);
      if (rigged) {
        note = std::move(*rigged);
        std::fprintf(stderr, "%.*s: note: %s\n", int(options.program.size()), options.program.data(), note.c_str());
        calibration = buildFaceRig(*face, options.rigmap, RigMapLookup::GivenOnly);
      } else if (!inPart) {
        return rigged.error();
      } else {  // its own rig still shows what it moves
        note = rigged.error().message + "; shown with its own targets only";
        std::fprintf(stderr, "%.*s: warning: %s\n", int(options.program.size()), options.program.data(), note.c_str());
      }
    }
  }
  if (!calibration) return calibration.error();
  auto rig = std::optional<facial::RigMapping>(std::move(calibration->rig));
  auto expressions =
      facial::ExpressionLibrary::load(options.expressions.empty() ? defaultExpressionsPath() : options.expressions);
  if (!expressions) return expressions.error();
  auto graphRig = facial::actionUnitRig(*rig, *expressions);
  if (!graphRig) return graphRig.error().prefixed(modelPath.string() + ": ");
  FaceSetup setup(std::move(*face), modelNameOf(modelPath), std::move(*rig), std::move(*graphRig),
                  std::move(*expressions));
  setup.autorigNote_ = std::move(note);
  return setup;
}

FaceSetup::FaceSetup(importers::LoadedFace face, std::string name, facial::RigMapping rig, facial::RigMapping graphRig,
                     facial::ExpressionLibrary expressions)
    : model_(std::move(face.model)),
      dressed_(std::move(face.dressed)),
      format_(face.format),
      vrm_(std::move(face.vrm)),
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
  return eng::makeError(eng::ErrorKind::NotFound, "unknown expression '" + std::string(name) + "'; available: " + available);
}

std::vector<const facial::ExpressionPreset*> FaceSetup::presets(bool compound) const {
  std::vector<const facial::ExpressionPreset*> picked;
  for (const facial::ExpressionPreset& preset : expressions_.presets())
    if (preset.isCompound() == compound) picked.push_back(&preset);
  return picked;
}

eng::Result<void> FaceSetup::expressionWeights(const facial::ExpressionPreset& preset, float intensity,
                                               std::span<float> weights, std::span<float> vrmExpressions) {
  if (!std::isfinite(intensity))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': intensity " + std::to_string(intensity) +
                          " is not a finite number");
  if (weights.size() != weightCount())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': " + std::to_string(weights.size()) +
                          " weights given, " + name_ + " has " + std::to_string(weightCount()));
  if (!vrmExpressions.empty() && vrmExpressions.size() != vrmExpressionCount())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': room for " + std::to_string(vrmExpressions.size()) +
                          " VRM expression weights, " + name_ + " has " + std::to_string(vrmExpressionCount()));
  const float clamped = std::clamp(intensity, 0.0f, 1.0f);
  if (auto au = facial::ExpressionLibrary::evaluate(preset, clamped, actionUnitScratch_); !au) return au.error();
  if (auto em = facial::ExpressionLibrary::evaluateEmotions(preset, clamped, emotionScratch_); !em) return em.error();
  std::copy(baseWeights_.begin(), baseWeights_.end(), weights.begin());
  return rig_.apply(actionUnitScratch_, emotionScratch_, weights, vrmExpressions);
}

}  // namespace app
