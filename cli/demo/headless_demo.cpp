// The demo without a display: the scripted tour through all seven states,
// rendered offscreen into numbered frames, an animated GIF and a contact
// sheet with one labelled tile per state, all under one output folder.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/view/face_framing.h"
#include "app/cli_parse.h"
#include "app/crowd_layout.h"
#include "cli/demo/demo_options.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/view_options.h"
#include "app/sequence_recorder.h"
#include "app/skeleton_motion.h"
#include "app/program_error.h"
#include "engine/image/contact_sheet.h"
#include "engine/scene/image_io.h"
#include "engine/vk/device/context.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "facial/character.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace cli {
namespace {

constexpr app::ErrorReporter fail{"facial demo"};

std::filesystem::path defaultOutputDir() {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  return std::filesystem::path("out") / (std::string("demo-") + stamp);
}

// Length of one pass through every state and back to the first. A state's
// exit time counts from the moment it is entered (its incoming blend
// included), so a pass is the sum of the exit times, plus the last blend back
// to the first state and a short settle.
float tourLength(const facial::StateMachineNode& machine) {
  float length = 0.0f, lastBlend = 0.0f;
  for (const facial::MachineState& state : machine.states)
    if (!state.transitions.empty()) {
      length += state.transitions.front().exitTime.value_or(0.0f);
      lastBlend = state.transitions.front().duration;
    }
  return length + lastBlend + 0.5f;
}

// Idle life that does not belong to the graph: a slow head sway and breathing.
glm::quat idleHeadTurn(float t, float phase) {
  return glm::angleAxis(glm::radians(2.5f) * std::sin(t * 0.45f + phase), glm::vec3(0, 1, 0)) *
         glm::angleAxis(glm::radians(1.2f) * std::sin(t * 0.31f + 1.3f * phase), glm::vec3(1, 0, 0));
}

glm::vec3 idleBreathing(float t, float phase, float size) {
  return glm::vec3(0.0f, 0.004f * size * std::sin(t * 1.6f + phase), 0.0f);
}

// Unskinned faces sway as a whole about `pivot`.
glm::mat4 idleMotion(float t, float phase, const glm::vec3& pivot, float size) {
  return glm::translate(glm::mat4(1.0f), pivot + idleBreathing(t, phase, size)) * glm::mat4_cast(idleHeadTurn(t, phase)) *
         glm::translate(glm::mat4(1.0f), -pivot);
}

// The tour's faces, posed frame by frame: one facial::Character per member of
// the crowd grid (app/crowd_layout.h), with the headless run's own idle sway
// and breathing (idleMotion above: repeatable frames for the goldens, so the
// characters' idle life is off), the --clip under it and the VRM material
// binds. Members of a crowd pick their own emotions at random moments.
class HeadlessCrowd {
 public:
  static eng::Result<HeadlessCrowd> create(const app::FaceSetup& setup, const facial::SharedGraphDefinition& graph,
                                           const std::filesystem::path& graphPath, const eng::Aabb& bounds,
                                           uint32_t crowd, const DemoOptions& o) {
    HeadlessCrowd c;
    c.bounds_ = bounds;
    c.offsets_ = app::crowdOffsets(crowd, bounds);
    // Skinned avatars turn the head joint instead of the whole model; --clip plays under every face.
    auto skeleton = app::SkeletonMotion::create(setup.model(), o.clip);
    if (!skeleton) return skeleton.error();
    auto materials = app::FaceMaterials::create(setup);  // VRM material binds, one set per face
    if (!materials) return materials.error();
    const std::vector<std::string> targetNames = setup.layout().names();
    const facial::CharacterParts parts{.graph = graph, .rig = &setup.graphRig(), .restWeights = setup.baseWeights(),
                                       .vrm = setup.vrm()};
    if (auto ok = app::checkCrowdBudget(crowd, *graph); !ok) return ok.error().prefixed(graphPath.string() + ": ");
    for (uint32_t i = 0; i < crowd; ++i) {
      auto face = facial::Character::create(parts, targetNames, {.seed = o.seed + i, .idleLife = false});
      if (!face) return face.error().prefixed(graphPath.string() + ": ");
      c.faces_.push_back(std::move(*face));
    }
    c.skeletons_.assign(crowd, *skeleton);
    c.materials_.assign(crowd, *materials);
    c.instances_.resize(crowd);
    c.nextTrigger_.assign(crowd, 0.0f);
    c.random_.seed(static_cast<uint32_t>(o.seed));
    return c;
  }

  const facial::Character& first() const { return faces_[0]; }
  const std::vector<glm::vec3>& offsets() const { return offsets_; }

  eng::Result<std::span<const eng::vk::ModelInstance>> pose(const app::FrameContext& frame, const eng::vk::GpuModel& model) {
    const size_t crowd = faces_.size();
    // The head sways about the neck: the bottom of the framed head, not its centre.
    const glm::vec3 swayPivot{bounds_.center().x, bounds_.min.y, bounds_.center().z};
    for (size_t i = 0; i < crowd; ++i) {
      if (crowd > 1 && frame.time >= nextTrigger_[i]) triggerRandomEmotion(i, frame.time);
      if (auto updated = faces_[i].update(frame.dt); !updated) return updated.error();
      if (auto moved = materials_[i].update(faces_[i].expressionWeights()); !moved) return moved.error();
      const float phase = 1.7f * float(i);
      const glm::mat4 place = glm::translate(glm::mat4(1.0f), offsets_[i]);
      if (skeletons_[i].turnsHeadJoint()) {
        skeletons_[i].update(frame.time, idleHeadTurn(frame.time, phase));
        instances_[i] = {&model, glm::translate(place, idleBreathing(frame.time, phase, bounds_.diagonal())),
                         faces_[i].weights(), skeletons_[i].nodeWorld()};
      } else {
        skeletons_[i].update(frame.time);
        instances_[i] = {&model, place * idleMotion(frame.time, phase, swayPivot, bounds_.diagonal()),
                         faces_[i].weights(), skeletons_[i].nodeWorld()};
      }
      instances_[i].materials = materials_[i].materials();
    }
    return std::span<const eng::vk::ModelInstance>(instances_);
  }

 private:
  HeadlessCrowd() = default;

  void triggerRandomEmotion(size_t i, float time) {
    // A graph without these parameters simply keeps playing.
    (void)faces_[i].setBool("autoplay", false);
    const char* name = kEmotions[size_t(std::uniform_int_distribution<int>(0, int(kEmotions.size()) - 1)(random_))];
    (void)faces_[i].trigger(name);
    nextTrigger_[i] = time + std::uniform_real_distribution<float>(1.5f, 4.0f)(random_);
  }

  eng::Aabb bounds_;
  std::vector<glm::vec3> offsets_;
  std::vector<facial::Character> faces_;
  std::vector<app::SkeletonMotion> skeletons_;
  std::vector<app::FaceMaterials> materials_;
  std::vector<eng::vk::ModelInstance> instances_;
  std::vector<float> nextTrigger_;
  std::mt19937 random_;
};

// One contact-sheet tile per state visit, taken once the state has been
// held a moment (after its blend has finished).
// The first frame of each state, 1.2 s in, picked when the frame is stepped
// (the face has moved on by the time a frame in flight comes back).
struct StateTiles {
  std::string machineName;
  std::vector<eng::ContactSheetTile> tiles;
  std::set<std::string> captured;
  std::map<uint32_t, std::string> picked;  // frame index -> state

  void note(uint32_t frame, const facial::Character& face) {
    const auto status = face.machineStatus(machineName);
    if (!status || status->blending) return;
    const std::string name(status->state);
    if (status->secondsInState >= 1.2f && captured.insert(name).second) picked.emplace(frame, name);
  }
  void capture(uint32_t frame, const eng::Image& image) {
    const auto it = picked.find(frame);
    if (it == picked.end()) return;
    eng::ContactSheetTile tile{eng::Canvas(image.width, image.height), it->second};
    tile.image.rgba = image.rgba8;
    tiles.push_back(std::move(tile));
  }
};

// The contact sheet of the states' tiles, four to a row, as outDir/contact_sheet.png.
eng::Result<std::filesystem::path> writeContactSheet(const std::vector<eng::ContactSheetTile>& tiles,
                                                     const std::string& faceName, const std::filesystem::path& outDir) {
  eng::ContactSheetOptions sheetOptions;
  sheetOptions.columns = std::min<int>(4, static_cast<int>(tiles.size()));
  sheetOptions.title = "facial demo tour: " + faceName;
  auto sheet = eng::composeContactSheet(tiles, sheetOptions);
  if (!sheet) return sheet.error();
  const std::filesystem::path sheetPath = outDir / "contact_sheet.png";
  if (auto written = eng::writePng(sheetPath, sheet->width, sheet->height, sheet->rgba); !written) return written.error();
  return sheetPath;
}

}  // namespace

int runHeadlessDemo(const DemoOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  uint32_t width = 384, height = 384;
  if (!o.size.empty() && !app::parseSize(o.size, width, height))
    return fail("--size '" + o.size + "' is not WxH (e.g. 384x384)");
  const uint32_t crowd = std::max<uint32_t>(1, o.crowd);
  if (crowd > 1024) return fail("--crowd must be at most 1024");

  auto framing = app::framingModeOption(o.frame);
  if (!framing) return fail(framing.error().message);
  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial demo"});
  if (!setup) return fail(setup.error().message);
  const std::filesystem::path graphPath = o.graph.empty() ? app::dataDirectory() / "graphs" / "tour.json" : std::filesystem::path(o.graph);
  auto graph = facial::loadGraph(graphPath, {.presets = facial::presetLookup(setup->expressions())});
  if (!graph) return fail(graph.error().message);
  const auto machineNode = (*graph)->findNode("emotions");
  const facial::StateMachineNode* machine = machineNode ? (*graph)->nodeAs<facial::StateMachineNode>(*machineNode) : nullptr;
  if (!machine) return fail(graphPath.string() + ": the demo needs a state machine node named \"emotions\"");

  // Crowd: a square grid of faces spaced by the framed part's size (the head,
  // by default), framed together.
  const eng::Aabb bounds = eng::framingBounds(setup->model(), *framing);
  auto faces = HeadlessCrowd::create(*setup, *graph, graphPath, bounds, crowd, o);
  if (!faces) return fail(faces.error().message);

  const std::filesystem::path outDir = o.out.empty() ? defaultOutputDir() : std::filesystem::path(o.out);
  std::printf("facial demo: no display, playing the tour headless into %s\n", outDir.string().c_str());
  std::fflush(stdout);

  // The tour's frames are written, not watched: auto draws them at high.
  auto quality = app::qualityOption(o.quality == app::kWindowQualityAuto ? "high" : o.quality);
  if (!quality) return fail(quality.error().message);
  auto renderers = app::SequenceRenderers::create(
      setup->displayModel(), {.width = width, .height = height, .device = o.device, .quality = *quality,
                              .framesInFlight = app::kSequenceFramesInFlight});
  if (!renderers) return fail(renderers.error().message);

  eng::vk::SceneView& view = renderers->view();
  view.camera = eng::OrbitCamera::frame(app::crowdBounds(faces->offsets(), bounds), float(width) / float(height));
  // A crowd is framed as a whole.
  if (crowd == 1) view.camera.zoom = faceViewZoom(setup->model(), *framing, eng::kFaceZoom, float(width) / float(height));

  app::SequenceOptions sequence;
  sequence.framesPerSecond = o.fps;
  sequence.seconds = o.seconds > 0.0f ? o.seconds : tourLength(*machine);
  sequence.frameDir = outDir / "frames";
  sequence.gifPath = outDir / "tour.gif";
  sequence.progressLabel = "tour";
  sequence.profile = o.profile;

  StateTiles states{"emotions"};
  auto summary = app::recordSequence(
      renderers->lanes(), sequence,
      [&](const app::FrameContext& frame) {
        auto posed = faces->pose(frame, renderers->gpuModel(frame.lane));
        if (posed) states.note(frame.index, faces->first());
        return posed;
      },
      [&](const app::FrameContext& frame, const eng::Image& image) { states.capture(frame.index, image); });
  if (!summary) return fail(summary.error().message);

  std::filesystem::path sheetPath;
  if (!states.tiles.empty()) {
    auto written = writeContactSheet(states.tiles, setup->name(), outDir);
    if (!written) return fail(written.error().message);
    sheetPath = *written;
  }
  if (auto clean = renderers->checkValidation(); !clean) return fail(clean.error().message);

  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("facial demo: %u frames of %ux%u (%u face%s, %.1f s at %.0f fps) in %.1f s, %.1f ms/frame render on %s\n",
              summary->frames, width, height, crowd, crowd == 1 ? "" : "s", sequence.seconds, o.fps, total,
              1000.0 * summary->renderSeconds / std::max<uint32_t>(1, summary->frames),
              renderers->deviceName().c_str());
  std::printf("  frames:        %s\n  animation:     %s\n", sequence.frameDir.string().c_str(),
              sequence.gifPath.string().c_str());
  if (!sheetPath.empty()) std::printf("  contact sheet: %s (%zu states)\n", sheetPath.string().c_str(), states.tiles.size());
  return 0;
}

}  // namespace cli
