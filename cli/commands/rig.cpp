// `facial rig MODEL [--rigmap FILE] [--shape NAME=VALUE]... [--json]`: how
// the runtime drives a face (any format loadFace reads): the rig mapping's
// scheme, how each emotion is realised (composed ones say from what), the
// VRM expression stage, visemes, the targets no input drives, the inputs that
// drive nothing, and the mapping's notes. A face that cannot show emotions is
// rigged on the fly as the posing commands do (app/face_autorig.h), and the
// report says which targets were made and which of its own were kept.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "app/face_autorig.h"
#include "app/face_setup.h"
#include "app/program_error.h"
#include "engine/scene/gltf_loader.h"
#include "facial/runtime/character/gaze_rig.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::rig_command {
namespace {

constexpr app::ErrorReporter fail{"facial rig"};

struct RigOptions {
  std::string model;
  std::string rigmap;
  std::vector<std::string> shapes;
  bool json = false;
  bool noAutorig = false;
};

// What rigging on the fly did (empty reason: nothing).
struct AutorigDone {
  std::string reason;
  app::CachedAutorig cached;
};

nlohmann::ordered_json autorigJson(const AutorigDone& done) {
  if (done.reason.empty()) return nullptr;
  return {{"reason", done.reason},
          {"made", done.cached.made},
          {"kept", done.cached.kept},
          {"warnings", done.cached.warnings},
          {"cache", done.cached.path.string()}};
}

void printAutorig(const AutorigDone& done) {
  if (done.reason.empty()) return;
  std::printf("autorig: %s; rigged with the built-in head's action units (%s %s)\n", done.reason.c_str(),
              done.cached.reused ? "from the cache" : "cached as", done.cached.path.string().c_str());
  std::string made, kept;
  for (const std::string& n : done.cached.made) made += (made.empty() ? "" : ", ") + n;
  for (const std::string& n : done.cached.kept) kept += (kept.empty() ? "" : ", ") + n;
  std::printf("  made (%zu): %s\n  kept (%zu): %s\n", done.cached.made.size(), made.c_str(), done.cached.kept.size(),
              kept.empty() ? "none" : kept.c_str());
  for (const std::string& w : done.cached.warnings) std::printf("  warning: %s\n", app::shortenNames(w).c_str());
}

nlohmann::ordered_json toJson(const std::string& modelPath, importers::FaceFormat format,
                              const facial::RigCalibration& calibration, const std::string& gaze, const AutorigDone& autorig) {
  const facial::RigMapping& rig = calibration.rig;
  const facial::RigMappingReport& report = rig.report();
  nlohmann::ordered_json units = nlohmann::ordered_json::array();
  for (const facial::ActionUnitCalibration& u : calibration.units)
    units.push_back({{"channel", u.channel}, {"reach", u.reach}, {"reference", u.reference}, {"scale", u.scale}});
  return {{"model", modelPath},
          {"format", std::string(importers::faceFormatName(format))},
          {"scheme", std::string(facial::rigSchemeName(report.scheme))},
          {"detail", report.detail},
          {"expressionStage", report.stage},
          {"emotions", report.emotions},
          {"visemes", report.visemes},
          {"speech", report.speech},
          {"unmappedExpressions", report.unmappedControls},
          {"targetCount", rig.targetCount()},
          {"drivenTargetCount", rig.drivenTargets().size()},
          {"unmappedTargets", report.unmappedTargets},
          {"unmappedInputs", report.unmappedInputs},
          {"notes", report.notes},
          {"gaze", gaze},
          {"autorig", autorigJson(autorig)},
          {"calibration", units}};
}

int runRig(const RigOptions& o) {
  auto face = importers::loadFace(o.model, {.shapes = o.shapes});
  if (!face) return fail(face.error().message);
  auto rig = app::buildFaceRig(*face, o.rigmap);
  AutorigDone autorig;
  if (!o.noAutorig) autorig.reason = app::autorigReason(*face, rig, o.rigmap);
  if (!autorig.reason.empty()) {
    auto cached = app::loadAutorigged(o.model, {.shapes = o.shapes}, *face);
    if (cached) {
      autorig.cached = std::move(*cached);
      rig = app::buildFaceRig(*face, o.rigmap, app::RigMapLookup::GivenOnly);
    } else {
      const std::string failed = app::cannotEmoteLine(o.model, autorig.reason, rig) + "; autorig: " + cached.error().message;
      if (!app::keepsOwnRig(*face, rig)) return fail(failed);
      // Its own rig (brows or lip corners, a VRM's expressions) is listed.
      std::fprintf(stderr, "facial rig: warning: %s; its own rig is listed\n", failed.c_str());
      autorig.reason.clear();
    }
  }
  if (!rig) return fail(rig.error().message);
  // Which morph targets steer the eyes (the window demo's idle life and facial::Character drive them).
  const std::vector<std::string> names = eng::WeightLayout(face->model).names();
  std::string gaze = facial::GazeRig::create(names, face->vrm.get()).describe();
  if (face->vrm && face->vrm->lookAt.type == facial::VrmLookAtType::Bone) gaze += " (VRM lookAt: eye bones)";
  if (o.json) {
    std::printf("%s\n",
                toJson(o.model, face->format, *rig, gaze, autorig).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace).c_str());
  } else {
    std::printf("%s (%s): %zu morph weight(s), %zu driven\n%s\n", o.model.c_str(),
                std::string(importers::faceFormatName(face->format)).c_str(), rig->rig.targetCount(),
                rig->rig.drivenTargets().size(), rig->rig.report().summary().c_str());
    std::printf("gaze: %s\n", gaze.c_str());
    printAutorig(autorig);
    if (!rig->units.empty())
      std::printf("action-unit strength calibration (largest vertex travel at 1 / face height):\n%s",
                  rig->summary().c_str());
  }
  return 0;
}

CommandRegistrar reg("rig", "Show how the expression runtime drives a model (rig mapping report)", [](CLI::App& app) {
  auto o = std::make_shared<RigOptions>();
  app.add_option("model", o->model, importers::kFaceFormatsHelp)->required();
  app.add_option("--rigmap", o->rigmap, "Rig map JSON to use instead of <data>/rigmaps/<model>.json or detection");
  app::addShapeOption(app, o->shapes);
  app.add_flag("--json", o->json, "Print machine-readable JSON instead of text");
  app.add_flag("--no-autorig", o->noAutorig,
               "Report a face that cannot show emotions as it is, instead of rigging it with the built-in head's "
               "action units first");
  return [o] { return runRig(*o); };
});

}  // namespace
}  // namespace cli::rig_command
