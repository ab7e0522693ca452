#include "app/face_setup.h"

#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <CLI/CLI.hpp>
#include <glm/gtc/constants.hpp>

#include "app/cli_parse.h"
#include "engine/core/log.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/obj_keyframes.h"
#include "importers/candide_import.h"
#include "importers/loop_subdivision.h"
#include "importers/vrm_import.h"
#include "facial/runtime/rig/action_unit_rig.h"
#include "facial/runtime/rig/action_units.h"

namespace app {

void addFaceOptions(CLI::App& app, std::string& model, std::string& rigmap) {
  app.add_option("--model,-m", model,
                 "Face: glTF / GLB, VRM, OBJ keyframe folder or CANDIDE-3 .wfm (default: the built-in head, <data>/head.glb)");
  app.add_option("--rigmap", rigmap,
                 "Rig map JSON naming which targets are which action unit or emotion "
                 "(default: <data>/rigmaps/<model>.json, else detected from the target names)");
}

void addShapeOption(CLI::App& app, std::vector<std::string>& shapes) {
  app.add_option("--shape", shapes,
                 "Identity parameter NAME=VALUE baked into the face before drawing (repeatable): a CANDIDE-3 "
                 "shape unit (e.g. 'mouth width=0.5', 'SU_Eyes_width=-0.3') or any morph target");
}

std::string_view faceFormatName(FaceFormat format) {
  switch (format) {
    case FaceFormat::Gltf: return "glTF";
    case FaceFormat::Vrm: return "VRM";
    case FaceFormat::ObjSet: return "OBJ keyframe set";
    case FaceFormat::Candide3: return "CANDIDE-3";
  }
  return "?";
}

namespace {

// Enough of the file to tell the formats apart.
constexpr size_t kSniffBytes = 64;

std::string shapeKey(std::string_view name) {
  std::string key;
  for (char c : name) key += (c == ' ' || c == '-') ? '_' : char(std::tolower(static_cast<unsigned char>(c)));
  if (key.compare(0, 3, "su_") == 0) key.erase(0, 3);
  return key;
}

eng::Result<LoadedFace> loadObjSet(const std::filesystem::path& dir) {
  auto folder = eng::findObjKeyframeFolder(dir);
  if (!folder) return folder.error();
  auto imported = eng::importObjKeyframes(folder->neutral, folder->targets);
  if (!imported) return imported.error();
  LoadedFace face{std::move(imported->model), FaceFormat::ObjSet, nullptr};
  face.model.sourcePath = dir.string();
  return face;
}

// VRM 0.x avatars face -Z (Unity's convention), glTF and VRM 1.0 faces +Z:
// the scene turns half a turn about +Y under a new root, as three-vrm's
// rotateVRM0 does, so the camera meets the face. Skinned meshes follow
// (their joints are under the new root).
void faceForward(eng::Model& model) {
  eng::Node turn;
  turn.name = "VRM 0.x faces +Z";
  turn.rotation = glm::angleAxis(glm::pi<float>(), glm::vec3(0.0f, 1.0f, 0.0f));
  turn.children = model.roots;
  const int index = int(model.nodes.size());
  for (int root : model.roots) model.nodes[size_t(root)].parent = index;
  model.nodes.push_back(std::move(turn));
  model.roots = {index};
}

eng::Result<LoadedFace> loadGltfOrVrm(const std::filesystem::path& path) {
  auto model = eng::loadModel(path);
  if (!model) return model.error();
  auto vrm = importers::findVrmExpressions(path);
  if (!vrm) return vrm.error();
  if (!*vrm) return LoadedFace{std::move(*model), FaceFormat::Gltf, nullptr};
  // The glTF loader skips the VRM extensions it does not know; here they are read.
  std::erase_if(model->warnings, [](const std::string& w) {
    return w == "optional extension VRM ignored" || w == "optional extension VRMC_vrm ignored";
  });
  const eng::WeightLayout layout(*model);
  const facial::VrmExpressionSet& set = **vrm;
  bool sameLayout = set.meshTargetOffsets.size() == size_t(layout.meshCount()) + 1;
  for (int m = 0; sameLayout && m <= layout.meshCount(); ++m) sameLayout = set.meshTargetOffsets[m] == layout.offset(m);
  if (!sameLayout)
    return eng::makeError(eng::ErrorKind::Malformed, path.string() + ": the VRM expressions address " + std::to_string(set.targetCount()) +
                          " morph targets over " + std::to_string(set.meshTargetOffsets.size() - 1) +
                          " meshes, the loaded model has " + std::to_string(layout.total()) + " over " +
                          std::to_string(layout.meshCount()));
  if (set.specVersion == 0) faceForward(*model);
  // What the VRM importer left out (a bind it cannot apply, ...): one line each, here and in `facial info`.
  for (const std::string& warning : set.warnings) {
    eng::logWarning(warning);
    model->warnings.push_back(warning);
  }
  return LoadedFace{std::move(*model), FaceFormat::Vrm, std::make_shared<const facial::VrmExpressionSet>(std::move(**vrm))};
}

}  // namespace

// The first bytes of a regular file.
static eng::Result<std::string> fileHead(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return eng::makeError(eng::ErrorKind::NotFound, path.string() + ": file not found");
  if (!std::filesystem::is_regular_file(status)) return eng::makeError(eng::ErrorKind::Io, path.string() + ": not a regular file or folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot open for reading");
  std::string head(kSniffBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

eng::Result<LoadedFace> loadFace(const std::filesystem::path& path, std::span<const std::string> shapes) {
  std::error_code ec;
  eng::Result<LoadedFace> face = eng::makeError(eng::ErrorKind::Malformed, "");
  if (std::filesystem::is_directory(path, ec)) {
    face = loadObjSet(path);
  } else {
    auto head = fileHead(path);
    if (!head) return head.error();
    const std::string_view text(*head);
    const size_t first = text.find_first_not_of(" \t\r\n");
    const std::string_view start = first == std::string_view::npos ? std::string_view() : text.substr(first);
    if (start.starts_with("glTF") || start.starts_with("{")) {
      face = loadGltfOrVrm(path);
    } else if (start.starts_with("# VERTEX LIST")) {
      auto model = importers::importCandide3(path);
      if (!model) return model.error();
      // 113 vertices shade and outline as facets: two Loop steps make the mask
      // (the first primitive; the others are its eyeballs) a smooth surface.
      eng::Mesh& mesh = model->meshes.front();
      for (int step = 0; step < 2; ++step)
        if (auto smooth = importers::loopSubdivide(mesh.primitives.front(), path.string() + ": " + mesh.name); !smooth)
          return smooth.error();
      face = LoadedFace{std::move(*model), FaceFormat::Candide3, nullptr};
    } else {
      return eng::makeError(eng::ErrorKind::Unsupported, path.string() + ": not a face this program reads (glTF / GLB, VRM, a folder of OBJ "
                            "keyframes or a CANDIDE-3 .wfm); the file starts with neither 'glTF', '{' nor '# VERTEX LIST'");
    }
  }
  if (!face) return face.error();
  if (auto baked = bakeShapes(face->model, shapes); !baked) return baked.error().prefixed(path.string() + ": ");
  return face;
}

eng::Result<void> bakeShapes(eng::Model& model, std::span<const std::string> shapes) {
  for (const std::string& assignment : shapes) {
    const size_t eq = assignment.rfind('=');
    float value = 0.0f;
    if (eq == std::string::npos || eq == 0 || !parseFloat(std::string_view(assignment).substr(eq + 1), value))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "--shape '" + assignment + "' is not NAME=VALUE with a finite number");
    const std::string name = assignment.substr(0, eq);
    // Exact names first, then the loose spelling.
    int matched = 0;
    for (bool loose : {false, true}) {
      for (eng::Mesh& mesh : model.meshes)
        for (size_t t = 0; t < mesh.targetNames.size(); ++t) {
          if (loose ? shapeKey(mesh.targetNames[t]) != shapeKey(name) : mesh.targetNames[t] != name) continue;
          for (eng::Primitive& prim : mesh.primitives) {
            const eng::MorphTarget& target = prim.targets[t];
            for (size_t v = 0; v < target.positions.size(); ++v) prim.positions[v] += value * target.positions[v];
            for (size_t v = 0; v < target.normals.size(); ++v) {
              const glm::vec3 n = prim.normals[v] + value * target.normals[v];
              if (glm::length(n) > 1e-6f) prim.normals[v] = glm::normalize(n);
            }
          }
          mesh.defaultWeights[t] = 0.0f;
          ++matched;
        }
      if (matched > 0) break;
    }
    if (matched == 0) {
      std::vector<std::string> candidates;
      for (const eng::Mesh& mesh : model.meshes)
        for (const std::string& t : mesh.targetNames)
          if (t.compare(0, 3, "SU_") == 0) candidates.push_back(t);
      if (candidates.empty())
        for (const eng::Mesh& mesh : model.meshes) candidates.insert(candidates.end(), mesh.targetNames.begin(), mesh.targetNames.end());
      std::string list;
      for (size_t i = 0; i < candidates.size() && i < 12; ++i) list += (i ? ", " : "") + candidates[i];
      if (candidates.size() > 12) list += ", ... (" + std::to_string(candidates.size()) + " in all)";
      return eng::makeError(eng::ErrorKind::NotFound, "--shape: no shape unit or morph target named '" + name + "'" +
                            (list.empty() ? std::string("; the model has none") : "; available: " + list));
    }
  }
  return {};
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
  if (!rig) return rig.error().prefixed(model.sourcePath + ": ");
  facial::RigCalibrationOptions calibration;
  if (const std::filesystem::path file = facial::rigMapFileFor(options); !file.empty()) {
    auto rigmap = facial::loadRigMapFile(file, targetNames);
    if (!rigmap) return rigmap.error().prefixed(model.sourcePath + ": ");
    calibration.overrides = std::move(rigmap->calibration);
  }
  auto calibrated = facial::calibrateRig(*rig, targetReach(model), calibration);
  if (!calibrated) return calibrated.error().prefixed(model.sourcePath + ": ");
  return calibrated;
}

eng::Result<facial::RigCalibration> buildFaceRig(const LoadedFace& face, const std::filesystem::path& rigmapFile) {
  if (!face.vrm) return buildModelRig(face.model, rigmapFile);
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(face.model.sourcePath);
  options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  auto rig = facial::buildVrmRigMapping(face.vrm, eng::WeightLayout(face.model).names(), options);
  if (!rig) return rig.error().prefixed(face.model.sourcePath + ": ");
  return facial::RigCalibration{std::move(*rig), {}};
}

eng::Result<FaceSetup> FaceSetup::load(const FaceSetupOptions& options) {
  const std::filesystem::path modelPath = options.model.empty() ? defaultModelPath() : options.model;
  auto face = loadFace(modelPath, options.shapes);
  if (!face) return face.error();
  auto calibration = buildFaceRig(*face, options.rigmap);
  if (!calibration) return calibration.error();
  auto rig = std::optional<facial::RigMapping>(std::move(calibration->rig));
  auto expressions =
      facial::ExpressionLibrary::load(options.expressions.empty() ? defaultExpressionsPath() : options.expressions);
  if (!expressions) return expressions.error();
  auto graphRig = facial::actionUnitRig(*rig, *expressions);
  if (!graphRig) return graphRig.error().prefixed(modelPath.string() + ": ");
  return FaceSetup(std::move(*face), modelNameOf(modelPath), std::move(*rig), std::move(*graphRig),
                   std::move(*expressions));
}

FaceSetup::FaceSetup(LoadedFace face, std::string name, facial::RigMapping rig, facial::RigMapping graphRig,
                     facial::ExpressionLibrary expressions)
    : model_(std::move(face.model)),
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
