// `facial autorig MODEL [--landmarks L.json] --out rigged.glb`: the face
// with the built-in head's action units and the ARKit 52 made for it
// (app/face_autorig.h), its own targets kept, written whole.
#include <cstdio>
#include <memory>
#include <string>
#include <system_error>

#include "app/face_autorig.h"
#include "app/face_setup.h"
#include "app/output_paths.h"
#include "app/program_error.h"
#include "cli/command.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::autorig_command {
namespace {

constexpr app::ErrorReporter fail{"facial autorig"};

struct AutorigOptions {
  std::string model;
  std::string landmarks;
  std::string landmarksOut;
  std::string out;
  bool noDetails = false;
};

// Refusals that need no work: an output that is an input (app::checkOutputs),
// or a rigged face that would not be glTF.
std::string checkPaths(const AutorigOptions& o) {
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext != ".glb" && ext != ".gltf") return "--out " + o.out + ": expected a .glb or .gltf file";
  // The landmarks beside the model are read only when they are there.
  std::error_code ec;
  const std::filesystem::path besidePath = app::landmarksBeside(o.model);
  const std::string beside = std::filesystem::exists(besidePath, ec) ? besidePath.string() : std::string();
  auto safe = app::checkOutputs({.inputs = {{"model", o.model}, {"--landmarks", o.landmarks}, {"", beside}},
                                 .outputs = {{"--out", o.out}, {"--landmarks-out", o.landmarksOut}}});
  return safe ? std::string() : safe.error().message;
}

std::string joined(const std::vector<std::string>& names, size_t most) {
  std::string s;
  for (size_t i = 0; i < names.size() && i < most; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > most) s += ", ... (" + std::to_string(names.size()) + ")";
  return s;
}

int runAutorig(const AutorigOptions& o) {
  if (std::string refused = checkPaths(o); !refused.empty()) return fail(refused);
  auto face = importers::loadFace(o.model, {.dressForDisplay = true});
  if (!face) return fail(face.error().message);
  if (!importers::isPlainMesh(face->format))
    return fail(o.model + ": a " + std::string(importers::faceFormatName(face->format)) +
                " face; autorig makes targets for glTF / GLB, OBJ and PLY faces (convert it first: facial convert)");
  // Allowed (ground truth is measured this way), but the rigged copy's action
  // units then take over from the face's own rig: say so.
  if (auto rig = app::buildFaceRig(*face); rig && app::autorigReason(*face, rig, {}).empty())
    std::fprintf(stderr, "facial autorig: warning: %s already shows emotions (%s rig); the rigged copy is driven by "
                 "the action units made for it instead\n", o.model.c_str(),
                 std::string(facial::rigSchemeName(rig->rig.scheme())).c_str());
  std::error_code ec;
  const std::filesystem::path beside = app::landmarksBeside(o.model);
  const std::filesystem::path landmarksFile =
      !o.landmarks.empty() ? std::filesystem::path(o.landmarks)
                           : (std::filesystem::is_regular_file(beside, ec) ? beside : std::filesystem::path());
  auto landmarks = app::faceLandmarks(*face, landmarksFile);
  if (!landmarks)
    return fail(landmarks.error().message +
                (landmarksFile.empty() ? "; pass --landmarks L.json (68 points, or write them to " + beside.string() + ")"
                                       : ""));
  if (!o.landmarksOut.empty())
    if (auto written = autorig::writeLandmarksFile(*landmarks, o.landmarksOut); !written)
      return fail(written.error().message);
  auto rigger = app::FaceAutorig::load();
  if (!rigger) return fail(rigger.error().message);
  auto rigged = rigger->rig(face->model, *landmarks, o.model, {.detailLayers = !o.noDetails});
  if (!rigged) return fail(rigged.error().message);
  if (auto saved = app::saveModelAtomically(rigged->model, o.out); !saved) return fail(saved.error().message);
  for (const std::string& w : rigged->report.warnings) app::printWarning("facial autorig", w);
  const app::TargetChanges changes = app::targetChanges(face->model, rigged->model);
  std::printf("wrote %s: %zu targets made (%s)", o.out.c_str(), changes.made.size(), joined(changes.made, 6).c_str());
  if (!changes.kept.empty())
    std::printf(", its %zu kept (%s)", changes.kept.size(), joined(changes.kept, 6).c_str());
  std::printf("\nlandmarks: %s\n", landmarks->source.c_str());
  for (const std::string& note : rigged->partNotes) std::printf("parts: %s\n", note.c_str());
  for (const std::string& note : rigged->report.notes) std::printf("units: %s\n", note.c_str());
  for (const std::string& line : rigged->report.details) std::printf("details: %s\n", line.c_str());
  return 0;
}

CommandRegistrar reg("autorig", "Make expression targets (FACS action units, ARKit 52) for a face that has none",
                     [](CLI::App& app) {
  auto o = std::make_shared<AutorigOptions>();
  app.add_option("model", o->model, "Face: glTF / GLB, or one OBJ file (a scan, a sculpt)")->required();
  app.add_option("--landmarks", o->landmarks,
                 "The face's 68 landmarks as JSON ({\"landmarks68\": [[x, y, z], ...]}, world space) instead of "
                 "finding them on a front view (default: <model stem>.landmarks.json beside the model, when there)");
  app.add_option("--landmarks-out", o->landmarksOut, "Also write the landmarks used, as a file --landmarks reads");
  app.add_option("--out,-o", o->out, "Output .glb / .gltf: the face with the new targets")->required();
  app.add_flag("--no-details", o->noDetails,
               "Shapes only: leave the face's textures as they are (no wrinkle and colour layers carried from the "
               "head; engines other than this one do not read them)");
  return [o] { return runAutorig(*o); };
});

}  // namespace
}  // namespace cli::autorig_command
