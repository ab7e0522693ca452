// `facial play FILE.json [--model M] [--rigmap R] [--clip NAME|N|all] [--fps N] [--seconds S] [--size WxH] --out DIR [--video out.gif]`
// Plays a graph (data/graphs/*.json) or a timeline (data/timelines/*.json)
// on a face, headless, into numbered PNG frames and optionally a GIF; with
// --clip, a skeletal animation of the model file plays under the face.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/view/face_framing.h"
#include "app/cli_parse.h"
#include "cli/command.h"
#include "app/view_options.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/sequence_recorder.h"
#include "app/skeleton_motion.h"
#include "app/program_error.h"
#include "app/output_paths.h"
#include "engine/core/json_nesting.h"
#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/rig/action_units.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::play_command {
namespace {

struct PlayOptions {
  std::string file;
  std::string model;
  std::string rigmap;
  bool noAutorig = false;
  std::string clip;  // skeletal clip of the model: name, index or "all"; empty = rest pose
  std::vector<std::string> shapes;
  std::string background;
  std::string device;
  std::string quality = "high";
  float fps = 24.0f;
  float seconds = 0.0f;  // 0: the timeline's length, or 24 s for a graph
  std::string size = "512x512";
  std::string frame = "face";
  std::string out;
  std::string video;
  bool allowOutsidePaths = false;
  bool profile = false;  // print where each frame's time went
};

constexpr app::ErrorReporter fail{"facial play"};

// A timeline file becomes a one-node graph so both kinds play the same way.
eng::Result<facial::SharedGraphDefinition> graphForTimeline(const app::FaceSetup& face, const std::string& file,
                                                            const nlohmann::json& document, float& length) {
  nlohmann::json channels = nlohmann::json::array();
  bool allActionUnits = true;
  for (const auto& track : document.value("tracks", nlohmann::json::array())) {
    const std::string channel = track.is_object() ? track.value("channel", "") : "";
    channels.push_back(channel);
    allActionUnits = allActionUnits && facial::actionUnitIndex(channel).has_value();
  }
  // The file's own mark wins (checked when the graph loads the file): an
  // imported glTF animation holds target weights even where the targets are
  // named like action units.
  const nlohmann::json mark = document.value("channels", nlohmann::json());
  if (mark == "targets") allActionUnits = false;
  else if (mark == "actionUnits") allActionUnits = true;
  length = document.value("duration", 0.0f);
  nlohmann::json graph = {
      {"version", facial::kGraphFileVersion},
      {"channels", allActionUnits ? nlohmann::json("actionUnits") : channels},
      {"timelines", {{"clip", std::filesystem::absolute(file).string()}}},
      {"root", {{"type", "timeline"}, {"timeline", "clip"}}},
  };
  facial::GraphLoadOptions options;
  options.presets = facial::presetLookup(face.expressions());
  options.allowOutsidePaths = true;  // the one file named is the user's own argument
  return facial::parseGraph(graph, file, options);
}

int runPlay(const PlayOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"file", o.file}, {"--model", o.model}, {"--rigmap", o.rigmap}},
                                     .outputs = {{"--video", o.video}},
                                     .frameFolders = {{"--out", o.out}}});
      !safe)
    return fail(safe.error().message);
  uint32_t width = 0, height = 0;
  if (!app::parseSize(o.size, width, height)) return fail("--size '" + o.size + "' is not WxH (e.g. 512x512)");
  std::ifstream in(o.file);
  if (!in) return fail(o.file + ": cannot open file");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (auto nesting = eng::checkJsonNesting(text, o.file); !nesting) return fail(nesting.error().message);
  nlohmann::json document = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object()) return fail(o.file + ": not a JSON object");

  auto framing = app::framingModeOption(o.frame);
  if (!framing) return fail(framing.error().message);
  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial play"});
  if (!setup) return fail(setup.error().message);

  float length = 24.0f;
  facial::GraphLoadOptions graphOptions;
  graphOptions.presets = facial::presetLookup(setup->expressions());
  graphOptions.allowOutsidePaths = o.allowOutsidePaths;
  eng::Result<facial::SharedGraphDefinition> graph =
      document.contains("tracks") ? graphForTimeline(*setup, o.file, document, length)
                                  : facial::loadGraph(o.file, graphOptions);
  if (!graph) return fail(graph.error().message);
  const std::vector<std::string> targetNames = setup->layout().names();
  auto face = facial::FaceDriver::create(*graph, &setup->graphRig(), targetNames, setup->baseWeights());
  if (!face) return fail(o.file + ": " + face.error().message);

  auto skeleton = app::SkeletonMotion::create(setup->model(), o.clip);
  if (!skeleton) return fail(skeleton.error().message);
  auto backdrop = app::parseBackground(o.background);
  if (!backdrop) return fail(backdrop.error().message);
  auto quality = app::qualityOption(o.quality);
  if (!quality) return fail(quality.error().message);

  auto renderers = app::SequenceRenderers::create(setup->displayModel(), {.width = width,
                                                                 .height = height,
                                                                 .zoom = faceViewZoom(setup->model(), *framing, eng::kFaceZoom,
                                                                                      float(width) / float(height)),
                                                                 .framing = *framing,
                                                                 .device = o.device,
                                                                 .backdrop = *backdrop,
                                                                 .quality = *quality,
                                                                 .framesInFlight = app::kSequenceFramesInFlight});
  if (!renderers) return fail(renderers.error().message);

  app::SequenceOptions sequence;
  sequence.framesPerSecond = o.fps;
  sequence.seconds = o.seconds > 0.0f ? o.seconds : length;
  sequence.frameDir = o.out;
  sequence.gifPath = o.video;
  sequence.progressLabel = "play";
  sequence.profile = o.profile;
  auto materials = app::FaceMaterials::create(*setup);  // VRM material binds follow the animated expressions
  if (!materials) return fail(materials.error().message);
  eng::vk::ModelInstance instance{&renderers->gpuModel(0), glm::mat4(1.0f), {}};
  auto summary = app::recordSequence(
      renderers->lanes(), sequence,
      [&](const app::FrameContext& frame) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        instance.model = &renderers->gpuModel(frame.lane);
        face->update(frame.dt);
        instance.weights = face->targetWeights();
        if (auto moved = materials->update(face->expressionWeights()); !moved) return moved.error();
        instance.materials = materials->materials();
        skeleton->update(frame.time);
        instance.nodeWorld = skeleton->nodeWorld();
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      });
  if (!summary) return fail(summary.error().message);
  if (auto clean = renderers->checkValidation(); !clean) return fail(clean.error().message);
  std::printf("played %s on %s: %u frames (%.1f s at %.0f fps) in %.1f s (%.1f ms/frame render) -> %s%s%s\n",
              o.file.c_str(), setup->name().c_str(), summary->frames, sequence.seconds, o.fps,
              summary->totalSeconds, 1000.0 * summary->renderSeconds / std::max<uint32_t>(1, summary->frames),
              o.out.c_str(), o.video.empty() ? "" : ", ", o.video.c_str());
  return 0;
}

CommandRegistrar reg("play", "Play a graph or timeline headless to PNG frames (and a GIF)", [](CLI::App& app) {
  auto o = std::make_shared<PlayOptions>();
  app.add_option("file", o->file, "Graph (data/graphs/*.json) or timeline (data/timelines/*.json)")->required();
  app::addFaceOptions(app, o->model, o->rigmap, o->noAutorig);
  app.add_option("--clip", o->clip,
                 "Skeletal animation of the model to play under the face: its name, its index, or 'all' (loops)");
  app::addShapeOption(app, o->shapes);
  app::addBackgroundOption(app, o->background);
  app.add_option("--fps", o->fps, "Frames per second")->capture_default_str();
  app.add_option("--seconds", o->seconds, "Length (default: the timeline's duration, 24 s for a graph)");
  app.add_option("--size", o->size, "Frame size WxH")->capture_default_str();
  app::addFramingOption(app, o->frame);
  app.add_option("--out,-o", o->out, "Folder for the numbered PNG frames")->required();
  app.add_option("--video", o->video, "Also write an animated GIF here");
  app.add_flag("--allow-outside-paths", o->allowOutsidePaths,
               "Let the graph name timeline files outside its own folder (absolute, ../)");
  app::addDeviceOption(app, o->device);
  app::addQualityOption(app, o->quality);
  app.add_flag("--profile", o->profile, "Print where each frame's time went (mean ms and share per stage)");
  return [o] { return runPlay(*o); };
});

}  // namespace
}  // namespace cli::play_command
