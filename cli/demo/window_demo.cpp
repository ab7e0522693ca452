// `facial demo` with a display: the face in a live window, driven by the
// tour graph's state machine with autoplay off. Keys 1-7 / the panel's
// buttons trigger the seven basic emotions (the graph eases between them);
// the intensity slider and the 2D pad override the graph while used (the
// pad drives a control-map node of its own graph); mouse drag orbits, the
// wheel zooms, F12 saves a screenshot, Esc quits. `--script` replays timed
// actions through the same paths (window_script.h); state changes are logged.
// `--crowd N`: N faces in a grid, each its own FaceDriver with random triggers.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "app/cli_parse.h"
#include "cli/demo/demo_options.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "cli/demo/window_idle_motion.h"
#include "app/skeleton_motion.h"
#include "engine/vk/present/imgui_layer.h"
#include "app/view_options.h"
#include "app/window_loop.h"
#include "app/window_script.h"
#include "engine/vk/device/context.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/present/window.h"
#include "engine/vk/present/window_renderer.h"
#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/control_map_node.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace cli {
namespace {

namespace fs = std::filesystem;

int fail(const std::string& message) {
  std::fprintf(stderr, "facial demo: error: %s\n", message.c_str());
  return 1;
}

// The seven triggers of the tour graph, in key order (1-7).
constexpr std::array<const char*, 7> kEmotions = {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"};
// The pad's graph: the study's 2D control map (ControlMapNode) with four
// presets on the axes around neutral, as labelled on the pad, and blinks on
// top so the face stays alive while it is held.
constexpr const char* kPadGraph = R"({
  "version": 1, "channels": "actionUnits",
  "parameters": [{"name": "padX", "type": "float", "default": 0}, {"name": "padY", "type": "float", "default": 0}],
  "root": {"type": "blink", "input": {"type": "controlMap", "name": "pad",
    "neutral": {"type": "pose", "preset": "neutral"},
    "right": {"type": "pose", "preset": "happy"}, "left": {"type": "pose", "preset": "sad"},
    "up": {"type": "pose", "preset": "surprise"}, "down": {"type": "pose", "preset": "anger"},
    "x": "padX", "y": "padY"}}})";

// Who decides the weights of the (single) face.
enum class Control { Graph, Slider, Pad };

// One animated face: its graph driver, idle motion, place in the grid and
// the weights it is drawn with this frame.
struct Face {
  facial::FaceDriver driver;
  IdleMotion idle;
  glm::mat4 placement{1.0f};
  float nextTrigger = 0.0f;  // crowd: when it picks a new emotion
  app::SkeletonMotion skeleton;   // the --clip and, on skinned avatars, the idle head turn
  float time = 0.0f;
  app::FaceMaterials materials;   // VRM material binds following the drawn expression weights
};

// The state machine whose current state the title shows: "emotions", else the first one.
std::optional<facial::NodeIndex> findStateMachine(const facial::GraphDefinition& graph) {
  if (auto node = graph.findNode("emotions"); node && graph.nodeAs<facial::StateMachineNode>(*node)) return node;
  for (facial::NodeIndex n = 0; n < graph.nodes().size(); ++n)
    if (graph.nodeAs<facial::StateMachineNode>(n)) return n;
  return std::nullopt;
}

const char* stateName(const facial::GraphInstance& graph, std::optional<facial::NodeIndex> machine) {
  if (!machine) return "graph";
  const auto status = graph.stateMachineStatus(*machine);
  const auto* node = graph.definition().nodeAs<facial::StateMachineNode>(*machine);
  if (!status || !node || status->current >= node->states.size()) return "graph";
  return node->states[status->current].name.c_str();
}

// F12's file: beside the --screenshot file when one is given, else in the
// current folder; "facial-<date>-<time>.png", "-2", "-3"... within a second.
fs::path screenshotPathFor(const DemoOptions& o) {
  char stamp[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "facial-%Y%m%d-%H%M%S", std::localtime(&now));
  const fs::path folder = o.screenshot.empty() ? fs::current_path() : fs::path(o.screenshot).parent_path();
  fs::path path = folder / (std::string(stamp) + ".png");
  std::error_code ec;
  for (int n = 2; fs::exists(path, ec); ++n) path = folder / (std::string(stamp) + "-" + std::to_string(n) + ".png");
  return path;
}

class WindowDemo {
 public:
  int run(const DemoOptions& o);

 private:
  int setUp(const DemoOptions& o);
  int setUpPad(const fs::path& graphPath);
  void drawPanel();
  void notePanelExtent();
  eng::vk::SceneView shownView() const;
  void handleInput();
  void runScript(float elapsed);
  void trigger(int emotion);
  void setIntensity(float intensity);
  void setPad(glm::vec2 cursor);
  void orbit(float yawDegrees, float pitchDegrees);
  void toggleFraming();
  void updateFaces(float dt);
  void logStateChange();
  void updateTitle(float dt);

  DemoOptions options_;
  std::optional<app::FaceSetup> setup_;
  facial::SharedGraphDefinition graph_;
  std::array<std::optional<facial::ParameterIndex>, kEmotions.size()> triggers_{};
  std::optional<facial::NodeIndex> machine_;
  std::vector<Face> faces_;
  std::vector<float> weights_;  // faces_.size() x weightCount, what is drawn
  std::vector<eng::vk::ModelInstance> instances_;

  // The single face's overrides: the override weights and how much of them
  // is shown (eased in and out). The slider poses a preset directly; the pad
  // moves the cursor of its own graph's control map (padDriver_).
  std::vector<float> overrideWeights_;
  std::vector<float> overrideExpressions_;  // the same for a VRM rig's expressions (material binds)
  std::vector<float> expressionScratch_;    // the single face's blended expression weights
  float overrideAmount_ = 0.0f;
  Control control_ = Control::Graph;
  Control lastOverride_ = Control::Slider;  // what overrideWeights_ shows while easing out
  int chosen_ = 1;  // the slider's expression (happy until a trigger says otherwise)
  float intensity_ = 1.0f;
  glm::vec2 pad_{0.0f};
  std::optional<facial::FaceDriver> padDriver_;
  facial::ParameterIndex padX_ = 0, padY_ = 0;
  std::vector<app::ScriptAction> script_;
  size_t nextAction_ = 0;
  std::string loggedState_;

  std::unique_ptr<eng::vk::Window> window_;
  std::optional<eng::vk::Context> ctx_;
  std::unique_ptr<eng::vk::WindowRenderer> renderer_;
  std::optional<eng::vk::GpuModel> gpuModel_;
  std::unique_ptr<eng::vk::ImGuiLayer> ui_;
  eng::vk::SceneView view_;
  eng::Aabb framedBounds_;                   // what view_ frames: the head(s), or the whole model(s)
  std::array<eng::Aabb, 2> crowdBounds_;     // by eng::FramingMode: the heads, the whole models
  eng::FramingMode framing_ = eng::FramingMode::Face;
  float panelLeft_ = 0.0f, panelRight_ = 0.0f, panelBottom_ = 0.0f;  // the panel this frame (ImGui pixels)
  bool orbiting_ = false;
  bool screenshotRequested_ = false;
  bool quitRequested_ = false;
  std::mt19937 random_;
  float frameMs_ = 0.0f;
  float titleTimer_ = 0.0f;
};

int WindowDemo::setUp(const DemoOptions& o) {
  options_ = o;
  random_.seed(uint32_t(o.seed));
  uint32_t width = 1280, height = 800;
  if (!o.size.empty() && !app::parseSize(o.size, width, height))
    return fail("--size '" + o.size + "' is not WxH (e.g. 1280x800)");

  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes});
  if (!setup) return fail(setup.error().message);
  setup_.emplace(std::move(*setup));
  const fs::path graphPath = o.graph.empty() ? app::dataDirectory() / "graphs" / "tour.json" : fs::path(o.graph);
  auto graph = facial::loadGraph(graphPath, {.presets = facial::presetLookup(setup_->expressions())});
  if (!graph) return fail(graph.error().message);
  graph_ = *graph;
  for (size_t e = 0; e < kEmotions.size(); ++e) {
    const auto p = graph_->findParameter(kEmotions[e]);
    if (p && graph_->parameters()[*p].type == facial::ParameterType::Trigger) triggers_[e] = p;
  }
  machine_ = findStateMachine(*graph_);
  const auto autoplay = graph_->findParameter("autoplay");

  const uint32_t count = setup_->weightCount();
  const uint32_t faceCount = std::max<uint32_t>(1, o.crowd);
  auto framing = app::framingModeOption(o.frame);
  if (!framing) return fail(framing.error().message);
  framing_ = *framing;
  const eng::Aabb bounds = eng::framingBounds(setup_->model(), framing_);
  const eng::Aabb other = eng::framingBounds(
      setup_->model(), framing_ == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face);
  const eng::Aabb faceBounds = eng::framingBounds(setup_->model(), eng::FramingMode::Face);
  const std::vector<std::string> names = setup_->layout().names();
  const uint32_t columns = uint32_t(std::ceil(std::sqrt(double(faceCount))));
  const glm::vec3 spacing = bounds.valid() ? bounds.size() * 1.15f : glm::vec3(1.0f);
  auto skeleton = app::SkeletonMotion::create(setup_->model(), o.clip);
  if (!skeleton) return fail(skeleton.error().message);
  auto materials = app::FaceMaterials::create(*setup_);
  if (!materials) return fail(materials.error().message);
  for (uint32_t i = 0; i < faceCount; ++i) {
    auto driver = facial::FaceDriver::create(graph_, &setup_->graphRig(), names, setup_->baseWeights(), o.seed + i);
    if (!driver) return fail(graphPath.string() + ": " + driver.error().message);
    if (autoplay) driver->graph().setBool(*autoplay, false);
    const uint32_t row = i / columns, column = i % columns;
    const uint32_t rows = (faceCount + columns - 1) / columns;
    const glm::vec3 offset((float(column) - 0.5f * float(columns - 1)) * spacing.x,
                           (0.5f * float(rows - 1) - float(row)) * spacing.y, 0.0f);
    auto idle = IdleMotion::create(names, setup_->vrm(), bounds, faceBounds, o.seed + i, o.still);
    if (!idle) return fail(idle.error().message);
    Face face{std::move(*driver), std::move(*idle), glm::translate(glm::mat4(1.0f), offset),
              std::uniform_real_distribution<float>(0.5f, 3.0f)(random_), *skeleton, 0.0f, *materials};
    crowdBounds_[size_t(framing_)].extend(eng::Aabb{bounds.min + offset, bounds.max + offset});
    crowdBounds_[1 - size_t(framing_)].extend(eng::Aabb{other.min + offset, other.max + offset});
    faces_.push_back(std::move(face));
  }
  weights_.assign(size_t(faceCount) * count, 0.0f);
  overrideWeights_.assign(setup_->baseWeights().begin(), setup_->baseWeights().end());
  overrideExpressions_.assign(setup_->vrmExpressionCount(), 0.0f);
  expressionScratch_.assign(setup_->vrmExpressionCount(), 0.0f);
  if (faceCount == 1)
    if (const int error = setUpPad(graphPath); error != 0) return error;
  if (!o.script.empty()) {
    auto script = app::loadWindowScript(o.script);
    if (!script) return fail(script.error().message);
    for (const app::ScriptAction& action : *script)
      if (action.kind == app::ScriptAction::Kind::Trigger && !graph_->findParameter(action.name))
        return fail(o.script + ": '" + action.name + "' is no trigger of " + graphPath.string());
    script_ = std::move(*script);
  }

  char title[256];
  std::snprintf(title, sizeof title, "facial demo - %s", setup_->name().c_str());
  auto window = eng::vk::Window::create({.width = int(width), .height = int(height), .title = title});
  if (!window) return fail("window: " + window.error().message);
  window_ = std::move(*window);
  eng::vk::ContextOptions contextOptions;
  contextOptions.device = options_.device;
  window_->configureContext(contextOptions);
  auto ctx = eng::vk::Context::create(contextOptions);
  if (!ctx) return fail("Vulkan: " + ctx.error().message);
  ctx_.emplace(std::move(*ctx));
  auto quality = app::windowQualityOption(options_.quality, ctx_->deviceInfo().type);
  if (!quality) return fail(quality.error().message);
  auto renderer = eng::vk::WindowRenderer::create(*ctx_, *window_, {.quality = *quality});
  if (!renderer) return fail("Vulkan: " + renderer.error().message);
  renderer_ = std::move(*renderer);
  auto gpuModel = renderer_->upload(setup_->displayModel());
  if (!gpuModel) return fail(gpuModel.error().message);
  gpuModel_.emplace(std::move(*gpuModel));

  auto ui = eng::vk::ImGuiLayer::create(*ctx_, *renderer_, *window_);
  if (!ui) return fail(ui.error().message);
  ui_ = std::move(*ui);

  view_.camera = eng::OrbitCamera::frame(crowdBounds_[size_t(framing_)], float(width) / float(height));
  framedBounds_ = crowdBounds_[size_t(framing_)];
  instances_.resize(faceCount);
  for (uint32_t i = 0; i < faceCount; ++i)
    instances_[i] = {&*gpuModel_, faces_[i].placement,
                     std::span<const float>(weights_).subspan(size_t(i) * count, count)};
  return 0;
}

int WindowDemo::setUpPad(const fs::path& graphPath) {
  auto document = facial::parseJsonText(kPadGraph, "the pad's graph");
  if (!document) return fail(document.error().message);
  auto graph = facial::parseGraph(*document, graphPath, {.presets = facial::presetLookup(setup_->expressions())});
  if (!graph) return fail(graph.error().message);
  auto driver = facial::FaceDriver::create(*graph, &setup_->graphRig(), setup_->layout().names(),
                                           setup_->baseWeights(), options_.seed);
  if (!driver) return fail("the pad's graph: " + driver.error().message);
  padX_ = *(*graph)->findParameter("padX");
  padY_ = *(*graph)->findParameter("padY");
  padDriver_.emplace(std::move(*driver));
  return 0;
}

void WindowDemo::setIntensity(float intensity) {
  intensity_ = std::clamp(intensity, 0.0f, 1.0f);
  auto preset = setup_->findExpression(kEmotions[chosen_]);
  if (!preset) return;
  control_ = lastOverride_ = Control::Slider;
  // lerp(neutral, preset, intensity): the preset at that intensity over the model's defaults.
  (void)setup_->expressionWeights(**preset, intensity_, overrideWeights_, overrideExpressions_);
}

void WindowDemo::setPad(glm::vec2 cursor) {
  if (!padDriver_) return;
  pad_ = glm::clamp(cursor, glm::vec2(-1.0f), glm::vec2(1.0f));
  padDriver_->graph().setFloat(padX_, pad_.x);
  padDriver_->graph().setFloat(padY_, pad_.y);
  control_ = lastOverride_ = Control::Pad;
}

void WindowDemo::orbit(float yawDegrees, float pitchDegrees) {
  view_.camera.yawDegrees += yawDegrees;
  view_.camera.pitchDegrees = std::clamp(view_.camera.pitchDegrees + pitchDegrees, -80.0f, 80.0f);
}

void WindowDemo::runScript(float elapsed) {
  // A pending screenshot holds the actions after it back: a shot shows
  // everything scripted before it and nothing after, however slow the frames.
  for (; nextAction_ < script_.size() && script_[nextAction_].time <= elapsed && !screenshotRequested_; ++nextAction_) {
    const app::ScriptAction& a = script_[nextAction_];
    std::printf("script: %.2f s\n", a.time);
    switch (a.kind) {
      case app::ScriptAction::Kind::Trigger: {
        const auto known = std::find(kEmotions.begin(), kEmotions.end(), a.name);
        if (known != kEmotions.end()) trigger(int(known - kEmotions.begin()));
        else if (const auto p = graph_->findParameter(a.name)) faces_[0].driver.graph().setTrigger(*p);
        break;
      }
      case app::ScriptAction::Kind::Intensity: setIntensity(a.a); break;
      case app::ScriptAction::Kind::Pad: setPad({a.a, a.b}); break;
      case app::ScriptAction::Kind::Graph: control_ = Control::Graph; break;
      case app::ScriptAction::Kind::Orbit: orbit(a.a, a.b); break;
      case app::ScriptAction::Kind::Frame: toggleFraming(); break;
      case app::ScriptAction::Kind::Screenshot: screenshotRequested_ = true; break;
      case app::ScriptAction::Kind::Resize: glfwSetWindowSize(window_->handle(), int(a.a), int(a.b)); break;
      case app::ScriptAction::Kind::Iconify: glfwIconifyWindow(window_->handle()); break;
      case app::ScriptAction::Kind::Restore: glfwRestoreWindow(window_->handle()); break;
    }
  }
}

void WindowDemo::trigger(int emotion) {
  if (!triggers_[emotion]) return;
  // The last press wins: triggers stay set until a transition consumes them,
  // and two presses within one frame would otherwise both be pending and
  // fire in the graph's priority order, not in the order they were pressed.
  facial::GraphInstance& graph = faces_[0].driver.graph();
  for (const auto& other : triggers_)
    if (other) graph.resetTrigger(*other);
  graph.setTrigger(*triggers_[emotion]);
  control_ = Control::Graph;
  if (emotion != 0) chosen_ = emotion;
}

// The camera re-framed on the heads or the whole models; the orbit angles
// and the zoom the user chose are kept.
void WindowDemo::toggleFraming() {
  const eng::FramingMode mode =
      framing_ == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face;
  framing_ = mode;
  framedBounds_ = crowdBounds_[size_t(mode)];
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float aspect = display.x > 0.0f && display.y > 0.0f ? display.x / display.y : 1.0f;
  const eng::OrbitCamera framed = eng::OrbitCamera::frame(framedBounds_, aspect, view_.camera.fovYDegrees);
  view_.camera.target = framed.target;
  view_.camera.distance = framed.distance;
  view_.camera.sceneRadius = framed.sceneRadius;
  std::printf("framing: %s\n", std::string(eng::framingModeName(mode)).c_str());
  std::fflush(stdout);
}

void WindowDemo::handleInput() {
  const ImGuiIO& io = ImGui::GetIO();
  for (const int key : window_->takeKeyPresses()) {
    if (key == GLFW_KEY_F12) screenshotRequested_ = true;
    if (io.WantTextInput) continue;
    if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + int(kEmotions.size())) trigger(key - GLFW_KEY_1);
    if (key == GLFW_KEY_F) toggleFraming();
    if (key == GLFW_KEY_ESCAPE) quitRequested_ = true;
  }

  // Orbit only with drags that start on the scene, not on the panel.
  // The press frame's delta is not part of the drag: it holds the pointer's
  // jump from wherever it was last seen (outside the window, before focus).
  const bool wasOrbiting = orbiting_;
  if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.WantCaptureMouse) orbiting_ = true;
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) orbiting_ = false;
  if (orbiting_ && wasOrbiting) orbit(-0.3f * io.MouseDelta.x, 0.3f * io.MouseDelta.y);
  if (!io.WantCaptureMouse && io.MouseWheel != 0.0f)
    view_.camera.zoom = std::clamp(view_.camera.zoom * std::pow(1.1f, io.MouseWheel), 0.3f, 8.0f);
}

// The face is framed in the part of the window the panel leaves free (the
// wider side of it), so a small window never hides half the face.
void WindowDemo::notePanelExtent() {
  panelLeft_ = ImGui::GetWindowPos().x;
  panelRight_ = panelLeft_ + ImGui::GetWindowSize().x;
  panelBottom_ = ImGui::GetWindowPos().y + ImGui::GetWindowSize().y;
}

eng::vk::SceneView WindowDemo::shownView() const {
  eng::vk::SceneView shown = view_;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  if (!(display.x > 0.0f) || !(display.y > 0.0f)) return shown;
  // Where the framed faces land in the whole window (their box's corners).
  const glm::mat4 viewProj = shown.camera.projection(display.x / display.y) * shown.camera.view();
  glm::vec2 lo(display.x, display.y), hi(0.0f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? framedBounds_.max.x : framedBounds_.min.x,
                      corner & 2 ? framedBounds_.max.y : framedBounds_.min.y,
                      corner & 4 ? framedBounds_.max.z : framedBounds_.min.z};
    const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return shown;
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(display.x, display.y);
    lo = glm::min(lo, pixel);
    hi = glm::max(hi, pixel);
  }
  // Only a panel that covers them moves the faces aside (a small panel in a corner does not).
  const bool covered = panelRight_ > lo.x && panelLeft_ < hi.x && panelBottom_ > lo.y;
  if (!covered) return shown;
  constexpr float kGap = 8.0f;
  const float rightFree = display.x - panelRight_ - kGap, leftFree = panelLeft_ - kGap;
  if (rightFree >= leftFree)
    shown.camera.fitToRegion(framedBounds_, {display.x, display.y}, {panelRight_ + kGap, 0.0f}, {display.x, display.y});
  else
    shown.camera.fitToRegion(framedBounds_, {display.x, display.y}, {0.0f, 0.0f}, {leftFree, display.y});
  return shown;
}

void WindowDemo::drawPanel() {
  ImGui::SetNextWindowPos({12, 12}, ImGuiCond_FirstUseEver);
  ImGui::Begin("facial", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%s: %.1f ms/frame (%.0f fps)", setup_->name().c_str(), frameMs_, frameMs_ > 0 ? 1000.0f / frameMs_ : 0.0f);
  if (faces_.size() > 1) {
    ImGui::Text("%zu faces, random triggers", faces_.size());
    notePanelExtent();
    ImGui::End();
    return;
  }
  ImGui::Text("state: %s%s", stateName(faces_[0].driver.graph(), machine_),
              control_ == Control::Slider ? " (slider)" : control_ == Control::Pad ? " (pad)" : "");
  ImGui::Separator();
  for (size_t e = 0; e < kEmotions.size(); ++e) {
    if (e % 4 != 0) ImGui::SameLine();
    char label[32];
    std::snprintf(label, sizeof label, "%zu %s", e + 1, kEmotions[e]);
    if (!triggers_[e]) ImGui::BeginDisabled();
    if (ImGui::Button(label, {86, 0})) trigger(int(e));
    if (!triggers_[e]) ImGui::EndDisabled();
  }

  ImGui::Separator();
  char sliderLabel[48];
  std::snprintf(sliderLabel, sizeof sliderLabel, "neutral -> %s", kEmotions[chosen_]);
  float intensity = intensity_;
  if (ImGui::SliderFloat(sliderLabel, &intensity, 0.0f, 1.0f, "%.2f") || ImGui::IsItemActive()) setIntensity(intensity);

  ImGui::Separator();
  ImGui::TextUnformatted("control map (drag): happy +x, sad -x, surprise +y, anger -y");
  const float side = 200.0f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("pad", {side, side});
  if (ImGui::IsItemActive()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    setPad({(m.x - origin.x) / side * 2.0f - 1.0f, 1.0f - (m.y - origin.y) / side * 2.0f});
  }
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 end{origin.x + side, origin.y + side}, mid{origin.x + side / 2, origin.y + side / 2};
  draw->AddRectFilled(origin, end, IM_COL32(30, 34, 44, 255), 4.0f);
  draw->AddRect(origin, end, IM_COL32(120, 130, 150, 255), 4.0f);
  draw->AddLine({origin.x, mid.y}, {end.x, mid.y}, IM_COL32(80, 90, 110, 255));
  draw->AddLine({mid.x, origin.y}, {mid.x, end.y}, IM_COL32(80, 90, 110, 255));
  // The map's reach: past the diamond |x| + |y| = 1 the cursor is pulled back onto it.
  const ImVec2 diamond[4] = {{end.x, mid.y}, {mid.x, origin.y}, {origin.x, mid.y}, {mid.x, end.y}};
  draw->AddPolyline(diamond, 4, IM_COL32(90, 110, 140, 255), ImDrawFlags_Closed, 1.0f);
  draw->AddText({end.x - 40, mid.y + 2}, IM_COL32(200, 200, 200, 255), "happy");
  draw->AddText({origin.x + 4, mid.y + 2}, IM_COL32(200, 200, 200, 255), "sad");
  draw->AddText({mid.x + 4, origin.y + 2}, IM_COL32(200, 200, 200, 255), "surprise");
  draw->AddText({mid.x + 4, end.y - 16}, IM_COL32(200, 200, 200, 255), "anger");
  const facial::ControlMapWeights reached = facial::controlMapWeights(pad_.x, pad_.y);
  const ImVec2 cursor{mid.x + reached.x * side / 2, mid.y - reached.y * side / 2};
  draw->AddCircleFilled(cursor, 6.0f, control_ == Control::Pad ? IM_COL32(255, 190, 90, 255) : IM_COL32(150, 150, 150, 255));
  if (control_ != Control::Graph && ImGui::Button("back to the graph")) control_ = Control::Graph;
  ImGui::TextDisabled("drag: orbit  wheel: zoom  F: face/whole model  F12: screenshot  Esc: quit");
  notePanelExtent();
  ImGui::End();
}

void WindowDemo::updateFaces(float dt) {
  const uint32_t count = setup_->weightCount();
  const bool crowd = faces_.size() > 1;
  // Overrides ease in and out over ~0.25 s so taking and releasing control never pops.
  const float towards = control_ == Control::Graph ? 0.0f : 1.0f;
  overrideAmount_ += std::clamp(towards - overrideAmount_, -4.0f * dt, 4.0f * dt);
  std::uniform_int_distribution<int> anyEmotion(0, int(kEmotions.size()) - 1);
  std::uniform_real_distribution<float> wait(2.0f, 5.0f);
  if (padDriver_ && (control_ == Control::Pad || (lastOverride_ == Control::Pad && overrideAmount_ > 0.0f))) {
    padDriver_->update(dt);
    const std::span<const float> pad = padDriver_->targetWeights();
    std::copy(pad.begin(), pad.end(), overrideWeights_.begin());
    const std::span<const float> padExpressions = padDriver_->expressionWeights();
    std::copy(padExpressions.begin(), padExpressions.end(), overrideExpressions_.begin());
  }
  for (size_t i = 0; i < faces_.size(); ++i) {
    Face& face = faces_[i];
    if (crowd) {
      face.nextTrigger -= dt;
      if (face.nextTrigger <= 0.0f) {
        if (const auto t = triggers_[anyEmotion(random_)]) face.driver.graph().setTrigger(*t);
        face.nextTrigger = wait(random_);
      }
    }
    face.driver.update(dt);
    // The eyes follow the viewer: the camera in this face's model space.
    const glm::vec3 viewer = glm::vec3(glm::inverse(face.placement) * glm::vec4(view_.camera.position(), 1.0f));
    face.idle.update(dt, viewer);
    std::span<float> out = std::span<float>(weights_).subspan(i * count, count);
    const std::span<const float> graphWeights = face.driver.targetWeights();
    std::span<const float> expressions = face.driver.expressionWeights();
    if (!crowd && overrideAmount_ > 0.0f) {
      for (uint32_t t = 0; t < count; ++t)
        out[t] = graphWeights[t] + overrideAmount_ * (overrideWeights_[t] - graphWeights[t]);
      for (size_t e = 0; e < expressions.size(); ++e)
        expressionScratch_[e] = expressions[e] + overrideAmount_ * (overrideExpressions_[e] - expressions[e]);
      expressions = expressionScratch_;
    } else {
      std::copy(graphWeights.begin(), graphWeights.end(), out.begin());
    }
    // Sizes were fixed at set-up and the weights come clamped from the rig: cannot fail.
    (void)face.materials.update(expressions);
    instances_[i].materials = face.materials.materials();
    face.idle.applyGaze(out);
    face.time += dt;
    const std::array<glm::quat, 2> eyeTurns{face.idle.eyeTurn(facial::Eye::Left), face.idle.eyeTurn(facial::Eye::Right)};
    if (face.skeleton.turnsHeadJoint()) {
      // A skinned avatar turns its head joint; the body only breathes.
      face.skeleton.update(face.time, face.idle.headTurn(), eyeTurns);
      instances_[i].transform = face.idle.breathing(face.placement);
    } else {
      face.skeleton.update(face.time, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), eyeTurns);
      instances_[i].transform = face.idle.transform(face.placement);
    }
    instances_[i].nodeWorld = face.skeleton.nodeWorld();
  }
}

// One line per state the single face enters, for logs and tests.
void WindowDemo::logStateChange() {
  if (faces_.size() != 1) return;
  const char* state = stateName(faces_[0].driver.graph(), machine_);
  if (loggedState_ == state) return;
  loggedState_ = state;
  std::printf("state: %s\n", state);
}

void WindowDemo::updateTitle(float dt) {
  frameMs_ = frameMs_ == 0.0f ? 1000.0f * dt : 0.9f * frameMs_ + 0.1f * 1000.0f * dt;
  titleTimer_ -= dt;
  if (titleTimer_ > 0.0f) return;
  titleTimer_ = 0.25f;
  char title[256];
  if (faces_.size() > 1)
    std::snprintf(title, sizeof title, "facial demo - %zu x %s - %.1f ms", faces_.size(), setup_->name().c_str(), frameMs_);
  else
    std::snprintf(title, sizeof title, "facial demo - %s - %s - %.1f ms", setup_->name().c_str(),
                  stateName(faces_[0].driver.graph(), machine_), frameMs_);
  glfwSetWindowTitle(window_->handle(), title);
}

int WindowDemo::run(const DemoOptions& o) {
  if (const int error = setUp(o); error != 0) return error;
  int exitCode = 0;
  auto frame = [&](const app::WindowTick& tick) -> eng::Result<app::WindowFramePlan> {
    ui_->beginFrame();
    handleInput();
    runScript(tick.animationTime);
    drawPanel();
    ui_->endFrame();
    updateFaces(tick.dt);
    logStateChange();
    updateTitle(tick.dt);
    app::WindowFramePlan plan{.input = {shownView(), instances_}, .quit = quitRequested_};
    plan.input.overlay = eng::vk::ImGuiLayer::recorder();
    // Kept requested until a frame is really presented (not skipped).
    if (screenshotRequested_) plan.requestedShot = screenshotPathFor(o);
    return plan;
  };
  auto shotWritten = [&](const fs::path& shot) {
    if (shot != fs::path(o.screenshot)) screenshotRequested_ = false;
  };
  if (auto ran = app::runWindowLoop(*window_, *renderer_, {.quitAfter = o.quitAfter, .finalScreenshot = o.screenshot},
                               frame, shotWritten);
      !ran)
    exitCode = fail(ran.error().message);
  int width = 0, height = 0;
  glfwGetWindowSize(window_->handle(), &width, &height);
  std::printf("demo: %s, %zu face(s), final state %s, %.1f ms/frame, camera yaw %.1f pitch %.1f, window %dx%d\n",
              setup_->name().c_str(), faces_.size(), stateName(faces_[0].driver.graph(), machine_), frameMs_,
              view_.camera.yawDegrees, view_.camera.pitchDegrees, width, height);
  ui_.reset();
  if (auto clean = ctx_->checkValidation(); !clean) return fail(clean.error().message);
  return exitCode;
}

}  // namespace

int runWindowDemo(const DemoOptions& options) {
  WindowDemo demo;
  return demo.run(options);
}

}  // namespace cli
