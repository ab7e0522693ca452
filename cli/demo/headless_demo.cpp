// The demo without a display: the scripted tour through all seven states,
// rendered offscreen into numbered frames, an animated GIF and a contact
// sheet with one labelled tile per state, all under one output folder.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/view/face_framing.h"
#include "app/cli_parse.h"
#include "cli/demo/demo_options.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/headless_model_renderer.h"
#include "app/view_options.h"
#include "app/sequence_recorder.h"
#include "app/skeleton_motion.h"
#include "engine/image/contact_sheet.h"
#include "engine/scene/image_io.h"
#include "engine/vk/device/context.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace cli {
namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "facial demo: error: %s\n", message.c_str());
  return 1;
}

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
  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes});
  if (!setup) return fail(setup.error().message);
  const std::filesystem::path graphPath = o.graph.empty() ? app::dataDirectory() / "graphs" / "tour.json" : std::filesystem::path(o.graph);
  facial::GraphLoadOptions graphOptions;
  graphOptions.presets = facial::presetLookup(setup->expressions());
  auto graph = facial::loadGraph(graphPath, graphOptions);
  if (!graph) return fail(graph.error().message);
  const auto machineNode = (*graph)->findNode("emotions");
  const facial::StateMachineNode* machine = machineNode ? (*graph)->nodeAs<facial::StateMachineNode>(*machineNode) : nullptr;
  if (!machine) return fail(graphPath.string() + ": the demo needs a state machine node named \"emotions\"");

  const std::vector<std::string> targetNames = setup->layout().names();
  std::vector<facial::FaceDriver> faces;
  auto materials = app::FaceMaterials::create(*setup);  // VRM material binds, one set per face
  if (!materials) return fail(materials.error().message);
  std::vector<app::FaceMaterials> faceMaterials(crowd, *materials);
  for (uint32_t i = 0; i < crowd; ++i) {
    auto face = facial::FaceDriver::create(*graph, &setup->graphRig(), targetNames, setup->baseWeights(), o.seed + i);
    if (!face) return fail(graphPath.string() + ": " + face.error().message);
    faces.push_back(std::move(*face));
  }

  const std::filesystem::path outDir = o.out.empty() ? defaultOutputDir() : std::filesystem::path(o.out);
  std::printf("facial demo: no display, playing the tour headless into %s\n", outDir.string().c_str());
  std::fflush(stdout);

  // The tour's frames are written, not watched: auto draws them at high.
  auto quality = app::qualityOption(o.quality == app::kWindowQualityAuto ? "high" : o.quality);
  if (!quality) return fail(quality.error().message);
  auto renderer = app::HeadlessModelRenderer::create(
      setup->displayModel(), {.width = width, .height = height, .device = o.device, .quality = *quality});
  if (!renderer) return fail(renderer.error().message);

  // Crowd: a square grid of faces spaced by the framed part's size (the head,
  // by default), framed together.
  const eng::Aabb bounds = eng::framingBounds(setup->model(), *framing);
  const uint32_t columns = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<float>(crowd))));
  const float spacing = std::max(bounds.size().x, bounds.size().y) * 1.15f;
  std::vector<glm::vec3> offsets(crowd);
  eng::Aabb crowdBounds;
  for (uint32_t i = 0; i < crowd; ++i) {
    offsets[i] = glm::vec3((float(i % columns) - 0.5f * float(columns - 1)) * spacing,
                           -(float(i / columns) - 0.5f * float((crowd - 1) / columns)) * spacing, 0.0f);
    crowdBounds.extend(bounds.min + offsets[i]);
    crowdBounds.extend(bounds.max + offsets[i]);
  }
  eng::vk::SceneView& view = renderer->view();
  view.camera = eng::OrbitCamera::frame(crowdBounds, float(width) / float(height));
  // A crowd is framed as a whole.
  if (crowd == 1) view.camera.zoom = faceViewZoom(setup->model(), *framing, eng::kFaceZoom, float(width) / float(height));

  // The head sways about the neck: the bottom of the framed head, not its centre.
  const glm::vec3 swayPivot{bounds.center().x, bounds.min.y, bounds.center().z};
  std::vector<eng::vk::ModelInstance> instances(crowd);
  // Skinned avatars turn the head joint instead of the whole model; --clip plays under every face.
  auto skeleton = app::SkeletonMotion::create(setup->model(), o.clip);
  if (!skeleton) return fail(skeleton.error().message);
  std::vector<app::SkeletonMotion> skeletons(crowd, *skeleton);
  std::mt19937 random(static_cast<uint32_t>(o.seed));
  std::vector<float> nextTrigger(crowd, 0.0f);
  static constexpr const char* kTriggers[] = {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"};

  app::SequenceOptions sequence;
  sequence.framesPerSecond = o.fps;
  sequence.seconds = o.seconds > 0.0f ? o.seconds : tourLength(*machine);
  sequence.frameDir = outDir / "frames";
  sequence.gifPath = outDir / "tour.gif";
  sequence.progressLabel = "tour";

  // One contact-sheet tile per state visit, taken once the state has been
  // held a moment (after its blend has finished).
  std::vector<eng::ContactSheetTile> tiles;
  std::set<std::string> captured;
  auto summary = app::recordSequence(
      renderer->offscreen(), view, sequence,
      [&](const app::FrameContext& frame) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        for (uint32_t i = 0; i < crowd; ++i) {
          if (crowd > 1 && frame.time >= nextTrigger[i]) {
            // Crowd members pick their own emotions at random moments.
            auto& g = faces[i].graph();
            if (auto autoplay = g.definition().findParameter("autoplay")) g.setBool(*autoplay, false);
            const char* name = kTriggers[std::uniform_int_distribution<int>(0, 6)(random)];
            if (auto trigger = g.definition().findParameter(name)) g.setTrigger(*trigger);
            nextTrigger[i] = frame.time + std::uniform_real_distribution<float>(1.5f, 4.0f)(random);
          }
          faces[i].update(frame.dt);
          if (auto moved = faceMaterials[i].update(faces[i].expressionWeights()); !moved) return moved.error();
          const float phase = 1.7f * float(i);
          const glm::mat4 place = glm::translate(glm::mat4(1.0f), offsets[i]);
          if (skeletons[i].turnsHeadJoint()) {
            skeletons[i].update(frame.time, idleHeadTurn(frame.time, phase));
            instances[i] = {&renderer->gpuModel(),
                            glm::translate(place, idleBreathing(frame.time, phase, bounds.diagonal())),
                            faces[i].targetWeights(), skeletons[i].nodeWorld()};
          } else {
            skeletons[i].update(frame.time);
            instances[i] = {&renderer->gpuModel(),
                            place * idleMotion(frame.time, phase, swayPivot, bounds.diagonal()),
                            faces[i].targetWeights(), skeletons[i].nodeWorld()};
          }
          instances[i].materials = faceMaterials[i].materials();
        }
        return std::span<const eng::vk::ModelInstance>(instances);
      },
      [&](const app::FrameContext&, const eng::Image& image) {
        const auto status = faces[0].graph().stateMachineStatus(*machineNode);
        if (!status || status->blending) return;
        const std::string& name = machine->states[status->current].name;
        if (status->stateTime >= 1.2f && captured.insert(name).second) {
          eng::ContactSheetTile tile{eng::Canvas(image.width, image.height), name};
          tile.image.rgba = image.rgba8;
          tiles.push_back(std::move(tile));
        }
      });
  if (!summary) return fail(summary.error().message);

  std::filesystem::path sheetPath;
  if (!tiles.empty()) {
    eng::ContactSheetOptions sheetOptions;
    sheetOptions.columns = std::min<int>(4, static_cast<int>(tiles.size()));
    sheetOptions.title = "facial demo tour: " + setup->name();
    auto sheet = eng::composeContactSheet(tiles, sheetOptions);
    if (!sheet) return fail(sheet.error().message);
    sheetPath = outDir / "contact_sheet.png";
    if (auto written = eng::writePng(sheetPath, sheet->width, sheet->height, sheet->rgba); !written)
      return fail(written.error().message);
  }
  if (auto clean = renderer->checkValidation(); !clean) return fail(clean.error().message);

  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("facial demo: %u frames of %ux%u (%u face%s, %.1f s at %.0f fps) in %.1f s, %.1f ms/frame render on %s\n",
              summary->frames, width, height, crowd, crowd == 1 ? "" : "s", sequence.seconds, o.fps, total,
              1000.0 * summary->renderSeconds / std::max<uint32_t>(1, summary->frames),
              renderer->deviceName().c_str());
  std::printf("  frames:        %s\n  animation:     %s\n", sequence.frameDir.string().c_str(),
              sequence.gifPath.string().c_str());
  if (!sheetPath.empty()) std::printf("  contact sheet: %s (%zu states)\n", sheetPath.string().c_str(), tiles.size());
  return 0;
}

}  // namespace cli
