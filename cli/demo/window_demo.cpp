// `facial demo` with a display: the face in a live window, driven by the
// tour graph's state machine with autoplay off. Keys 1-7 / the panel's
// buttons trigger the seven basic emotions (the graph eases between them);
// the intensity slider and the 2D pad override the graph while used (the
// pad drives a control-map node of its own graph); mouse drag orbits, the
// wheel zooms, F12 saves a screenshot, Esc quits. `--script` replays timed
// actions through the same paths (window_script.h); state changes are logged.
// `--crowd N`: N faces in a grid, each its own facial::Character with random triggers.
// The Speak box (app/speech_box.h) makes the single face say a typed line
// aloud: audio::LiveSpeech synthesizes and plays it, and the mouth follows
// the audio clock (silently, with one note, when there is no sound card).
//
// The parts: the faces (demo_faces.h, one facial::Character each), the
// panel's hold on the single face (face_override.h), the camera
// (demo_camera.h), the window (app/window_session.h, app/window_loop.h);
// this file is the panel, the input and the script over them.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>

#include "app/cli_parse.h"
#include "app/face_setup.h"
#include "app/program_error.h"
#include "app/speech_box.h"
#include "app/view_options.h"
#include "app/window_loop.h"
#include "app/window_script.h"
#include "app/window_session.h"
#include "audio/live_speech.h"
#include "cli/demo/demo_camera.h"
#include "cli/demo/demo_faces.h"
#include "cli/demo/demo_options.h"
#include "cli/demo/face_override.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/control_map_node.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace cli {
namespace {

namespace fs = std::filesystem;

constexpr app::ErrorReporter fail{"facial demo"};

// The state machine whose current state the title shows: "emotions", else the first one (an empty name).
std::string_view shownMachine(const facial::GraphDefinition& graph) {
  const auto node = graph.findNode("emotions");
  return node && graph.nodeAs<facial::StateMachineNode>(*node) ? "emotions" : "";
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
  int loadScript(const fs::path& graphPath);
  int openWindow(uint32_t width, uint32_t height);
  glm::vec2 displaySize() const;
  void drawPanel();
  void drawPad();
  void speak();
  void stopSpeaking(const char* why);
  void followSpeech();
  void notePanelExtent();
  void handleInput();
  void runScript(float elapsed);
  void trigger(int emotion);
  void toggleFraming();
  void updateFaces(float dt);
  std::string stateName() const;
  void logStateChange();
  void updateTitle(float dt);

  DemoOptions options_;
  std::optional<app::FaceSetup> setup_;
  facial::SharedGraphDefinition graph_;
  std::array<bool, kEmotions.size()> hasTrigger_{};  // which of kEmotions the graph triggers
  std::string machine_;                              // the state machine the title shows (empty: the first)
  std::optional<DemoFaces> faces_;
  std::optional<FaceOverride> override_;
  std::optional<DemoCamera> camera_;
  std::vector<app::ScriptAction> script_;
  size_t nextAction_ = 0;
  std::string loggedState_;
  audio::LiveSpeech speech_;
  app::SpeechBox speechBox_;
  float speechTime_ = 0.0f;

  std::unique_ptr<app::WindowSession> session_;
  std::optional<eng::vk::GpuModel> gpuModel_;  // destroyed before the session
  bool orbiting_ = false;
  bool screenshotRequested_ = false;
  bool quitRequested_ = false;
  float frameMs_ = 0.0f;
  float titleTimer_ = 0.0f;
};

int WindowDemo::setUp(const DemoOptions& o) {
  options_ = o;
  speech_ = audio::LiveSpeech({.silent = o.mute});
  uint32_t width = 1280, height = 800;
  if (!o.size.empty() && !app::parseSize(o.size, width, height))
    return fail("--size '" + o.size + "' is not WxH (e.g. 1280x800)");

  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial demo"});
  if (!setup) return fail(setup.error().message);
  setup_.emplace(std::move(*setup));
  const fs::path graphPath = o.graph.empty() ? app::dataDirectory() / "graphs" / "tour.json" : fs::path(o.graph);
  auto graph = facial::loadGraph(graphPath, {.presets = facial::presetLookup(setup_->expressions())});
  if (!graph) return fail(graph.error().message);
  graph_ = *graph;
  for (size_t e = 0; e < kEmotions.size(); ++e) {
    const auto p = graph_->findParameter(kEmotions[e]);
    hasTrigger_[e] = p && graph_->parameters()[*p].type == facial::ParameterType::Trigger;
  }
  machine_ = shownMachine(*graph_);

  auto framing = app::framingModeOption(o.frame);
  if (!framing) return fail(framing.error().message);
  auto faces = DemoFaces::create(*setup_, graph_, graphPath, *framing, hasTrigger_, o);
  if (!faces) return fail(faces.error().message);
  faces_.emplace(std::move(*faces));
  auto hold = FaceOverride::create(*setup_, graphPath, o.seed, /*withPad=*/!faces_->crowd());
  if (!hold) return fail(hold.error().message);
  override_.emplace(std::move(*hold));
  if (const int error = loadScript(graphPath); error != 0) return error;
  if (const int error = openWindow(width, height); error != 0) return error;
  camera_.emplace(faces_->bounds(), *framing, float(width) / float(height));
  return 0;
}

// The --script file; the triggers it names are checked before the window opens.
int WindowDemo::loadScript(const fs::path& graphPath) {
  if (options_.script.empty()) return 0;
  auto script = app::loadWindowScript(options_.script);
  if (!script) return fail(script.error().message);
  for (const app::ScriptAction& action : *script)
    if (action.kind == app::ScriptAction::Kind::Trigger && !graph_->findParameter(action.name))
      return fail(options_.script + ": '" + action.name + "' is no trigger of " + graphPath.string());
  script_ = std::move(*script);
  return 0;
}

int WindowDemo::openWindow(uint32_t width, uint32_t height) {
  char title[256];
  std::snprintf(title, sizeof title, "facial demo - %s", setup_->name().c_str());
  auto session = app::WindowSession::open(
      {.width = width, .height = height, .title = title, .device = options_.device, .quality = options_.quality,
       .timeFrames = options_.profile});
  if (!session) return fail(session.error().message);
  session_ = std::move(*session);
  auto gpuModel = session_->renderer().upload(setup_->displayModel());
  if (!gpuModel) return fail(gpuModel.error().message);
  gpuModel_.emplace(std::move(*gpuModel));
  faces_->bind(*gpuModel_);
  return 0;
}

glm::vec2 WindowDemo::displaySize() const {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  return {display.x, display.y};
}

void WindowDemo::runScript(float elapsed) {
  // A pending screenshot holds the actions after it back: a shot shows
  // everything scripted before it and nothing after, however slow the frames.
  for (; nextAction_ < script_.size() && script_[nextAction_].time <= elapsed && !screenshotRequested_; ++nextAction_) {
    const app::ScriptAction& a = script_[nextAction_];
    std::printf("script: %.2f s\n", a.time);
    GLFWwindow* window = session_->window().handle();
    switch (a.kind) {
      case app::ScriptAction::Kind::Trigger: {
        const auto known = std::find(kEmotions.begin(), kEmotions.end(), a.name);
        if (known != kEmotions.end()) trigger(int(known - kEmotions.begin()));
        else (void)faces_->single().trigger(a.name);  // checked at set-up: one of the graph's parameters
        break;
      }
      case app::ScriptAction::Kind::Intensity: override_->setIntensity(a.a); break;
      case app::ScriptAction::Kind::Pad: override_->setPad({a.a, a.b}); break;
      case app::ScriptAction::Kind::Graph: override_->returnToGraph(); break;
      case app::ScriptAction::Kind::Orbit: camera_->orbit(a.a, a.b); break;
      case app::ScriptAction::Kind::Frame: toggleFraming(); break;
      case app::ScriptAction::Kind::Screenshot: screenshotRequested_ = true; break;
      case app::ScriptAction::Kind::Resize: glfwSetWindowSize(window, int(a.a), int(a.b)); break;
      case app::ScriptAction::Kind::Iconify: glfwIconifyWindow(window); break;
      case app::ScriptAction::Kind::Restore: glfwRestoreWindow(window); break;
      case app::ScriptAction::Kind::Say:
        speechBox_.setText(a.name);
        speak();
        break;
      case app::ScriptAction::Kind::SayLanguage: speechBox_.setLanguage(a.name); break;
      case app::ScriptAction::Kind::SayStop: stopSpeaking("stopped"); break;
    }
  }
}

void WindowDemo::trigger(int emotion) {
  if (!hasTrigger_[size_t(emotion)]) return;
  // The last press wins: triggers stay set until a transition consumes them,
  // and two presses within one frame would otherwise both be pending and
  // fire in the graph's priority order, not in the order they were pressed.
  facial::Character& face = faces_->single();
  for (size_t e = 0; e < kEmotions.size(); ++e)
    if (hasTrigger_[e]) (void)face.resetTrigger(kEmotions[e]);
  (void)face.trigger(kEmotions[size_t(emotion)]);
  override_->chooseEmotion(emotion);
}

void WindowDemo::toggleFraming() {
  const eng::FramingMode mode = camera_->toggleFraming(displaySize());
  std::printf("framing: %s\n", std::string(eng::framingModeName(mode)).c_str());
  std::fflush(stdout);
}

void WindowDemo::handleInput() {
  const ImGuiIO& io = ImGui::GetIO();
  for (const int key : session_->window().takeKeyPresses()) {
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
  if (orbiting_ && wasOrbiting) camera_->orbit(-0.3f * io.MouseDelta.x, 0.3f * io.MouseDelta.y);
  if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) camera_->zoom(io.MouseWheel);
}

// The face is framed in the part of the window the panel leaves free.
void WindowDemo::notePanelExtent() {
  const float left = ImGui::GetWindowPos().x;
  camera_->notePanel(left, left + ImGui::GetWindowSize().x, ImGui::GetWindowPos().y + ImGui::GetWindowSize().y);
}

void WindowDemo::drawPanel() {
  ImGui::SetNextWindowPos({12, 12}, ImGuiCond_FirstUseEver);
  ImGui::Begin("facial", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%s: %.1f ms/frame (%.0f fps)", setup_->name().c_str(), frameMs_, frameMs_ > 0 ? 1000.0f / frameMs_ : 0.0f);
  if (faces_->crowd()) {
    ImGui::Text("%zu faces, random triggers", faces_->size());
    notePanelExtent();
    ImGui::End();
    return;
  }
  const Control control = override_->control();
  ImGui::Text("state: %s%s", stateName().c_str(),
              control == Control::Slider ? " (slider)" : control == Control::Pad ? " (pad)" : "");
  ImGui::Separator();
  for (size_t e = 0; e < kEmotions.size(); ++e) {
    if (e % 4 != 0) ImGui::SameLine();
    char label[32];
    std::snprintf(label, sizeof label, "%zu %s", e + 1, kEmotions[e]);
    if (!hasTrigger_[e]) ImGui::BeginDisabled();
    if (ImGui::Button(label, {86, 0})) trigger(int(e));
    if (!hasTrigger_[e]) ImGui::EndDisabled();
  }

  ImGui::Separator();
  char sliderLabel[48];
  std::snprintf(sliderLabel, sizeof sliderLabel, "neutral -> %s", kEmotions[size_t(override_->chosen())]);
  float intensity = override_->intensity();
  if (ImGui::SliderFloat(sliderLabel, &intensity, 0.0f, 1.0f, "%.2f") || ImGui::IsItemActive())
    override_->setIntensity(intensity);

  ImGui::Separator();
  drawPad();
  ImGui::Separator();
  switch (speechBox_.draw({.speaking = speech_.speaking(), .time = speechTime_, .seconds = float(speech_.lineSeconds())},
                          ImGui::GetContentRegionAvail().x)) {
    case app::SpeechBox::Action::Speak: speak(); break;
    case app::SpeechBox::Action::Stop: stopSpeaking("stopped"); break;
    case app::SpeechBox::Action::None: break;
  }
  if (override_->control() != Control::Graph && ImGui::Button("back to the graph")) override_->returnToGraph();
  ImGui::TextDisabled("drag: orbit  wheel: zoom  F: face/whole model  F12: screenshot  Esc: quit");
  notePanelExtent();
  ImGui::End();
}

// The control map pad: drag to move its cursor; drawn with its axes' presets and its reach.
void WindowDemo::drawPad() {
  ImGui::TextUnformatted("control map (drag): happy +x, sad -x, surprise +y, anger -y");
  const float side = 200.0f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("pad", {side, side});
  if (ImGui::IsItemActive()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    override_->setPad({(m.x - origin.x) / side * 2.0f - 1.0f, 1.0f - (m.y - origin.y) / side * 2.0f});
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
  const glm::vec2 pad = override_->pad();
  const facial::ControlMapWeights reached = facial::controlMapWeights(pad.x, pad.y);
  const ImVec2 cursor{mid.x + reached.x * side / 2, mid.y - reached.y * side / 2};
  draw->AddCircleFilled(cursor, 6.0f,
                        override_->control() == Control::Pad ? IM_COL32(255, 190, 90, 255) : IM_COL32(150, 150, 150, 255));
}

// The box's line, replacing the one playing; a problem shows under the box and in the log.
void WindowDemo::speak() {
  if (faces_->crowd()) return;
  auto track = speech_.start(speechBox_.text(), speechBox_.language());
  if (track) {
    if (auto spoken = faces_->single().speak(*track); !spoken) {
      speech_.stop();
      track = spoken.error();
    }
  }
  if (!track) return speechBox_.reportProblem("facial demo", track.error().message);
  speechBox_.reportStarted("facial demo", speech_.describe(), speech_.takeNotes());
  // The slider's or pad's pose covers the whole face, mouth included: the
  // graph takes the face back to speak (the slider's emotion, triggered).
  if (override_->control() == Control::Slider) trigger(override_->chosen());
  override_->returnToGraph();
}

void WindowDemo::stopSpeaking(const char* why) {
  speech_.stop();
  if (faces_->crowd() || !faces_->single().speaking()) return;
  faces_->single().stopSpeaking();
  std::printf("facial demo: speech: %s\n", why);
  std::fflush(stdout);
}

// The mouth at the time of the sample being heard (the audio clock, not the frame clock).
void WindowDemo::followSpeech() {
  if (const std::optional<float> time = speech_.update()) {
    speechTime_ = *time;
    (void)faces_->single().setSpeechTime(*time);  // the player's clock is finite
  } else {
    stopSpeaking("done");
  }
}

void WindowDemo::updateFaces(float dt) {
  override_->update(dt);
  if (!faces_->crowd()) {
    override_->applyTo(faces_->single());
    followSpeech();
  }
  faces_->update(dt, camera_->camera().position());
}

std::string WindowDemo::stateName() const {
  const auto state = faces_->single().currentState(machine_);
  return state ? std::string(*state) : std::string("graph");
}

// One line per state the single face enters, for logs and tests.
void WindowDemo::logStateChange() {
  if (faces_->crowd()) return;
  const std::string state = stateName();
  if (loggedState_ == state) return;
  loggedState_ = state;
  std::printf("state: %s\n", state.c_str());
}

void WindowDemo::updateTitle(float dt) {
  frameMs_ = frameMs_ == 0.0f ? 1000.0f * dt : 0.9f * frameMs_ + 0.1f * 1000.0f * dt;
  titleTimer_ -= dt;
  if (titleTimer_ > 0.0f) return;
  titleTimer_ = 0.25f;
  char title[256];
  if (faces_->crowd())
    std::snprintf(title, sizeof title, "facial demo - %zu x %s - %.1f ms", faces_->size(), setup_->name().c_str(), frameMs_);
  else
    std::snprintf(title, sizeof title, "facial demo - %s - %s - %.1f ms", setup_->name().c_str(), stateName().c_str(),
                  frameMs_);
  glfwSetWindowTitle(session_->window().handle(), title);
}

int WindowDemo::run(const DemoOptions& o) {
  if (const int error = setUp(o); error != 0) return error;
  int exitCode = 0;
  auto frame = [&](const app::WindowTick& tick) -> eng::Result<app::WindowFramePlan> {
    session_->ui().beginFrame();
    handleInput();
    runScript(tick.animationTime);
    drawPanel();
    session_->ui().endFrame();
    updateFaces(tick.dt);
    logStateChange();
    updateTitle(tick.dt);
    app::WindowFramePlan plan{.input = {camera_->shownView(displaySize()), faces_->instances()}, .quit = quitRequested_};
    plan.input.overlay = eng::vk::ImGuiLayer::recorder();
    // Kept requested until a frame is really presented (not skipped).
    if (screenshotRequested_) plan.requestedShot = screenshotPathFor(o);
    return plan;
  };
  auto shotWritten = [&](const fs::path& shot) {
    if (shot != fs::path(o.screenshot)) screenshotRequested_ = false;
  };
  if (auto ran = app::runWindowLoop(session_->window(), session_->renderer(),
                                    {.quitAfter = o.quitAfter, .finalScreenshot = o.screenshot, .profile = o.profile}, frame, shotWritten);
      !ran)
    exitCode = fail(ran.error().message);
  int width = 0, height = 0;
  glfwGetWindowSize(session_->window().handle(), &width, &height);
  std::printf("demo: %s, %zu face(s), final state %s, %.1f ms/frame, camera yaw %.1f pitch %.1f, window %dx%d\n",
              setup_->name().c_str(), faces_->size(), stateName().c_str(), frameMs_, camera_->camera().yawDegrees,
              camera_->camera().pitchDegrees, width, height);
  if (auto clean = session_->finish(); !clean) return fail(clean.error().message);
  return exitCode;
}

}  // namespace

int runWindowDemo(const DemoOptions& options) {
  WindowDemo demo;
  return demo.run(options);
}

}  // namespace cli
