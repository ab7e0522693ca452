// `facial timeline import MODEL [--animation N|NAME] --out T.json`
// `facial timeline export T.json --model M [--node N] --out OUT.glb`
// Moves keyframe timelines between glTF `weights` animations and the
// project's JSON timeline format (data/timelines/*.json), so an animation
// made in Blender or Maya can be edited, layered in a graph and played, and a
// timeline authored here can be shipped on the model for any glTF viewer.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/command.h"
#include "app/face_setup.h"
#include "app/program_error.h"
#include "app/output_paths.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "bake/gltf_timeline.h"
#include "facial/runtime/graph/timeline_json.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::timeline_command {
namespace {

struct TimelineOptions {
  std::string model;
  std::string animation;  // index or name; empty: the first animation with weights channels
  std::string timeline;
  int node = -1;
  std::string out;
};

constexpr app::ErrorReporter fail{"facial timeline"};

// The index of the animation named or numbered `which` among those that
// animate weights, or an error listing what the model has.
eng::Result<size_t> pickAnimation(const eng::Model& model, const std::string& which) {
  std::string available;
  for (size_t i = 0; i < model.animations.size(); ++i) {
    if (model.animations[i].channels.empty()) continue;
    if (which.empty() || which == model.animations[i].name || which == std::to_string(i)) return i;
    available += (available.empty() ? "" : ", ") + std::to_string(i) + " '" + model.animations[i].name + "'";
  }
  if (available.empty()) return eng::makeError(eng::ErrorKind::NotFound, model.sourcePath + ": has no animation of morph target weights");
  return eng::makeError(eng::ErrorKind::NotFound, model.sourcePath + ": no weights animation '" + which + "' (it has: " + available + ")");
}

int runImport(const TimelineOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"model", o.model}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  auto face = importers::loadFace(o.model);
  if (!face) return fail(face.error().message);
  eng::Model* model = &face->model;
  auto index = pickAnimation(*model, o.animation);
  if (!index) return fail(index.error().message);
  std::vector<std::string> warnings;
  auto timeline = bake::importGltfTimeline(*model, *index, &warnings);
  if (!timeline) return fail(o.model + ": " + timeline.error().message);
  for (const std::string& warning : warnings) app::printWarning("facial timeline", warning);
  if (auto saved = facial::saveTimeline(*timeline, o.out); !saved) return fail(saved.error().message);
  std::printf("wrote %s: animation '%s' of %s, %zu track(s), %.3f s\n", o.out.c_str(), timeline->name.c_str(),
              o.model.c_str(), timeline->tracks.size(), timeline->duration);
  return 0;
}

int runExport(const TimelineOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"timeline", o.timeline}, {"--model", o.model}}, .outputs = {{"--out", o.out}}});
      !safe)
    return fail(safe.error().message);
  auto timeline = facial::loadTimeline(o.timeline);
  if (!timeline) return fail(timeline.error().message);
  auto face = importers::loadFace(o.model);
  if (!face) return fail(face.error().message);
  eng::Model* model = &face->model;
  if (auto exported = bake::exportGltfTimeline(*model, *timeline, {.node = o.node}); !exported)
    return fail(o.timeline + " on " + o.model + ": " + exported.error().message);
  size_t droppedChannels = 0;
  for (const eng::Animation& animation : model->animations) droppedChannels += animation.otherChannelCount;
  if (droppedChannels > 0)
    std::fprintf(stderr,
                 "facial timeline: warning: %s has %zu node transform channel(s); the project keeps only morph "
                 "weights, so %s will not have them\n",
                 o.model.c_str(), droppedChannels, o.out.c_str());
  if (auto saved = eng::saveModel(*model, o.out); !saved) return fail(saved.error().message);
  std::printf("wrote %s: %s with animation '%s' (%zu track(s), %.3f s)\n", o.out.c_str(), o.model.c_str(),
              timeline->name.c_str(), timeline->tracks.size(), timeline->duration);
  return 0;
}

CommandRegistrar reg(
    "timeline", "Convert between glTF weights animations and JSON timelines (import / export)", [](CLI::App& app) {
      auto o = std::make_shared<TimelineOptions>();
      app.require_subcommand(1);
      CLI::App* import = app.add_subcommand("import", "A glTF weights animation -> a JSON timeline");
      import->add_option("model", o->model, "glTF/GLB model with a weights animation")->required();
      import->add_option("--animation,-a", o->animation, "Animation index or name (default: the first)");
      import->add_option("--out,-o", o->out, "Timeline JSON to write")->required();
      CLI::App* exporter = app.add_subcommand("export", "A JSON timeline -> a glTF animation on the model");
      exporter->add_option("timeline", o->timeline, "Timeline JSON (data/timelines/*.json format)")->required();
      exporter->add_option("--model,-m", o->model, "glTF/GLB model whose morph targets the tracks name")->required();
      exporter->add_option("--node", o->node, "Node whose mesh is animated (default: the first with a mesh)");
      exporter->add_option("--out,-o", o->out, "Model to write (.glb or .gltf)")->required();
      return [o, import] { return import->parsed() ? runImport(*o) : runExport(*o); };
    });

}  // namespace
}  // namespace cli::timeline_command
