#include "editor/app/editor_app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "app/cli_parse.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/output_paths.h"
#include "app/view_options.h"
#include "engine/vk/present/imgui_layer.h"
#include "app/window_loop.h"
#include "app/window_session.h"
#include "editor/app/bilinear_pad_panel.h"
#include "editor/app/control_map_panel.h"
#include "editor/app/editor_script.h"
#include "editor/app/face_delegate.h"
#include "editor/app/menu_bar.h"
#include "editor/app/project_actions.h"
#include "editor/app/landmark_panel.h"
#include "editor/app/sculpt_panel.h"
#include "editor/app/state_machine_panel.h"
#include "editor/app/timeline_panel.h"
#include "editor/app/tooltip.h"
#include "editor/app/driver_channels.h"
#include "editor/key_recorder.h"
#include "engine/view/framing_bounds.h"
#include "importers/face_dressing.h"

namespace editor {

namespace {

namespace fs = std::filesystem;

// Panel layout: fixed columns and a bottom strip, the face in the middle.
struct Layout {
  float width = 0, height = 0;
  float top = 0;        // the menu bar
  float side = 0;       // left and right column width
  float bottom = 0;     // timeline strip height
  float leftSplit = 0;  // state machine / control map boundary
  // The free viewport rectangle.
  float x0() const { return side; }
  float x1() const { return width - side; }
  float y1() const { return height - bottom; }

  static Layout of(float width, float height, float top) {
    Layout l;
    l.width = width;
    l.height = height;
    l.top = top;
    l.side = std::clamp(width * 0.25f, 240.0f, 340.0f);
    l.bottom = std::clamp(height * 0.3f, 170.0f, 280.0f);
    l.leftSplit = top + (height - top - l.bottom) * 0.5f;
    return l;
  }
};

class EditorApp : public FaceDelegate, public ProjectViewHost {
 public:
  int run(const EditorOptions& o);

  // FaceDelegate
  float currentValue(std::string_view channel) const override;
  FaceSource source() const override { return source_; }
  void takeControl(FaceSource source) override { source_ = source; }

  // ProjectViewHost
  ProjectView viewSettings() const override;
  void applyViewSettings(const ProjectView& view) override;

 private:
  int setUp(const EditorOptions& o);
  void drawPanels();
  void handleViewportInput();
  // The viewport's mouse actions, shared by the mouse and the script.
  bool pickAt(float px, float py);
  bool dragSelectedByPixels(float dx, float dy);
  void orbit(float yawDegrees, float pitchDegrees);
  // Runs the script's actions due by `elapsed`; stops at a screenshot until it is written.
  void runScript(float elapsed);
  bool runAction(const EditorScriptAction& action);
  void logTimeline() const;
  void logView() const;
  // The state machine diagram, the bilinear pad and Record (issue 34, points 3 and 4).
  bool runGraphOrPadAction(const EditorScriptAction& action);
  bool startRecording();
  bool stopRecording();
  void sampleRecording(float dt);
  void drawPadWindow();
  void drawControlPoints();
  eng::OrbitCamera renderCamera() const;
  glm::vec3 panelBackground() const;
  // World ray through a window pixel.
  void rayAt(float px, float py, glm::vec3& origin, glm::vec3& direction) const;
  std::span<const float> faceWeights() const;
  // The face source's VRM expression weights (material binds); empty unless the rig has an expression stage.
  std::span<const float> faceExpressionWeights() const;
  eng::Result<void> uploadDisplayModel();
  // Projects, export and the menu bar (editor/app/project_actions.h, menu_bar.h).
  void setFraming(eng::FramingMode framing);
  bool runProjectAction(const EditorScriptAction& action);
  void runMenuRequest(const MenuRequest& request);
  void updateProjectAndTitle();
  // Open: in this editor, or (a project on another face) in a new one after this closes.
  bool openProject(const fs::path& path, size_t scriptNext, float scriptTime);

 public:
  // Set when run() ended to open a project made on another face (runEditor starts the next editor).
  fs::path reopen;
  size_t reopenScriptFrom = 0;
  float reopenClock = 0.0f;

 private:
  static void onWindowClose(GLFWwindow* window);
  // The view camera as a picture (the window): what the landmarks are projected with.
  autorig::PictureCamera pictureCamera() const;
  VkRect2D viewRegionPixels() const;

  std::optional<app::FaceSetup> setup_;
  StateMachinePanel machine_;
  ControlMapPanel controlMap_;
  BilinearPadPanel bilinearPad_;
  KeyRecorder recorder_;
  std::vector<float> recordValues_;  // one frame's channel values, reused
  float recordElapsed_ = 0.0f;
  int showPadTab_ = -1;  // a pad tab the script brings forward (0 control map, 1 bilinear), -1 none
  std::unique_ptr<TimelinePanel> timeline_;
  SculptPanel sculpt_;
  LandmarkPanel landmarks_;
  bool landmarkDragging_ = false;
  uint64_t uploadedRigRevision_ = 0;
  FaceSource source_ = FaceSource::StateMachine;
  std::vector<std::string> targetNames_;

  std::unique_ptr<app::WindowSession> session_;
  std::optional<eng::vk::GpuModel> gpuModel_;  // destroyed before the session
  uint64_t uploadedRevision_ = 0;
  eng::vk::SceneView view_;  // camera: target = face centre, user yaw / pitch / zoom
  eng::Aabb bounds_;  // what the camera frames: the head (F: the whole model)
  eng::FramingMode framing_ = eng::FramingMode::Face;
  Layout layout_;
  std::vector<float> displayWeights_;
  app::FaceMaterials materials_;  // VRM material binds following the shown expression weights
  std::vector<glm::vec3> pointsOnFace_, pointsMoved_;  // control point markers, reused every frame
  eng::vk::ModelInstance instance_;
  bool orbiting_ = false;
  bool sculptDragging_ = false;
  fs::path defaultShot_;  // where F12 writes
  fs::path pendingShot_;  // a screenshot asked for (F12, the script), written with the next presented frame
  std::vector<EditorScriptAction> script_;
  size_t nextAction_ = 0;
  size_t failedActions_ = 0;
  bool quitRequested_ = false;
  float frameMs_ = 0.0f;
  MenuBar menu_;
  std::optional<ProjectActions> project_;
  std::string title_;  // the window's, as last set
  bool quitDiscarded_ = false;  // Quit > Discard: nothing is kept
};

EditorApp* gEditor = nullptr;  // for the window's close callback (one editor a process)

float EditorApp::currentValue(std::string_view channel) const {
  switch (source_) {
    case FaceSource::StateMachine: return driverChannelValue(machine_.driver(), targetNames_, channel);
    case FaceSource::ControlMap: return driverChannelValue(controlMap_.active(), targetNames_, channel);
    case FaceSource::Timeline: {
      TimelineDocument& doc = timeline_->document();
      if (const auto track = doc.findTrack(channel)) return doc.sample(*track, timeline_->playhead());
      const auto it = std::find(targetNames_.begin(), targetNames_.end(), channel);
      return it == targetNames_.end() ? 0.0f : timeline_->targetWeights()[size_t(it - targetNames_.begin())];
    }
    case FaceSource::BilinearPad: return bilinearPad_.channelValue(channel);
  }
  return 0.0f;
}

std::span<const float> EditorApp::faceWeights() const {
  switch (source_) {
    case FaceSource::StateMachine: return machine_.targetWeights();
    case FaceSource::ControlMap: return controlMap_.targetWeights();
    case FaceSource::Timeline: return timeline_->targetWeights();
    case FaceSource::BilinearPad: return bilinearPad_.targetWeights();
  }
  return machine_.targetWeights();
}

std::span<const float> EditorApp::faceExpressionWeights() const {
  switch (source_) {
    case FaceSource::StateMachine: return machine_.driver().expressionWeights();
    case FaceSource::ControlMap: return controlMap_.active().expressionWeights();
    case FaceSource::Timeline: return timeline_->expressionWeights();
    case FaceSource::BilinearPad: return bilinearPad_.expressionWeights();
  }
  return machine_.driver().expressionWeights();
}

int EditorApp::setUp(const EditorOptions& o) {
  uint32_t width = 1280, height = 800;
  if (!app::parseSize(o.size, width, height)) return fail("--size '" + o.size + "' is not WxH (e.g. 1280x800)");
  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .dressForDisplay = false,
                                      .autorig = !o.noAutorig, .program = "facial-editor"});
  if (!setup) return fail(setup.error().message);
  setup_.emplace(std::move(*setup));
  targetNames_ = setup_->layout().names();
  auto materials = app::FaceMaterials::create(*setup_);
  if (!materials) return fail(materials.error().message);
  materials_ = std::move(*materials);
  std::printf("facial-editor: %s, %u morph targets, rig %s\n", setup_->name().c_str(), setup_->weightCount(),
              std::string(facial::rigSchemeName(setup_->rig().scheme())).c_str());

  const std::string graphPath = o.graph.empty() ? (app::dataDirectory() / "graphs" / "tour.json").string() : o.graph;
  if (auto loaded = machine_.load(*setup_, graphPath); !loaded) return fail(loaded.error().message);
  if (o.mute) machine_.muteSpeech();
  if (!o.trigger.empty() && !machine_.fire(o.trigger))
    return fail(graphPath + ": no trigger parameter named '" + o.trigger + "'");
  if (auto created = controlMap_.create(*setup_); !created) return fail(created.error().message);
  if (auto created = bilinearPad_.create(*setup_); !created) return fail(created.error().message);
  timeline_ = std::make_unique<TimelinePanel>(*setup_);
  if (!o.timeline.empty() && !timeline_->open(o.timeline)) return 1;  // the panel logged why
  // Landmarks are in the built-in head's space: offered for that model only.
  const bool builtIn = o.model.empty() || fs::weakly_canonical(o.model) == fs::weakly_canonical(app::defaultModelPath());
  const std::string landmarks = builtIn ? (app::dataDirectory() / "head_landmarks.json").string() : std::string();
  if (auto created = sculpt_.create(*setup_, landmarks); !created) return fail(created.error().message);
  project_.emplace(ProjectPanels{&*setup_, &machine_, timeline_.get(), &sculpt_, this}, o.model, o.rigmap, o.graph);
  defaultShot_ = o.screenshot.empty() ? fs::path("facial-editor.png") : fs::path(o.screenshot);
  if (!o.script.empty()) {
    // Names the script needs are checked before the window opens.
    auto script = loadEditorScript(o.script);
    if (!script) return fail(script.error().message);
    for (const EditorScriptAction& a : *script) {
      if (a.kind == EditorScriptAction::Kind::Trigger && !machine_.hasTrigger(a.text))
        return fail(a.source + ": no trigger parameter '" + a.text + "' in " + graphPath);
      if (a.kind == EditorScriptAction::Kind::SculptLandmark && !sculpt_.hasLandmark(a.text))
        return fail(a.source + ": '" + a.text + "' is not one of the sculpt panel's landmarks" +
                    (builtIn ? " (the surface and position landmarks of data/head_landmarks.json)"
                             : " (landmarks exist for the built-in head only)"));
      using Kind = EditorScriptAction::Kind;
      const bool writes = a.kind == Kind::TimelineSave || a.kind == Kind::SculptSave || a.kind == Kind::Screenshot ||
                          a.kind == Kind::GraphSave || a.kind == Kind::ProjectSave || a.kind == Kind::GraphSave || a.kind == Kind::ProjectSaveAs || a.kind == Kind::ExportGlb || a.kind == Kind::ExportGif ||
                          a.kind == Kind::ExportVideo;
      if (auto safe = app::checkOutputs({.inputs = {{"--model", o.model}, {"--rigmap", o.rigmap}, {"--graph", graphPath}, {"--script", o.script}},
                                         .outputs = {{"", writes ? std::string_view(a.text) : std::string_view()}}});
          !safe)
        return fail(a.source + ": " + safe.error().message);
    }
    script_ = std::move(*script);
    // Resumed in a new editor (a project on another face): the actions before are done, the clock goes on.
    script_.erase(script_.begin(), script_.begin() + std::ptrdiff_t(std::min(o.scriptFrom, script_.size())));
    for (EditorScriptAction& a : script_) a.time = std::max(0.0f, a.time - o.scriptClockFrom);
  }

  auto session = app::WindowSession::open({.width = width,
                                           .height = height,
                                           .title = "facial editor - " + setup_->name(),
                                           .applicationName = "facial-editor",
                                           .device = o.device,
                                           .quality = o.quality,
                                           .timeFrames = o.profile});
  if (!session) return fail(session.error().message);
  session_ = std::move(*session);

  bounds_ = eng::framingBounds(setup_->model(), framing_);
  view_.camera = eng::OrbitCamera::frame(bounds_, 1.0f);
  if (auto uploaded = uploadDisplayModel(); !uploaded) return fail(uploaded.error().message);
  if (!o.project.empty() && !project_->open(o.project)) return 1;  // it said why
  gEditor = this;
  glfwSetWindowCloseCallback(session_->window().handle(), &EditorApp::onWindowClose);
  return 0;
}

eng::Result<void> EditorApp::uploadDisplayModel() {
  sculpt_.refresh();
  if (gpuModel_ && uploadedRevision_ == sculpt_.displayRevision() && uploadedRigRevision_ == landmarks_.riggedRevision()) return {};
  // The old model may still be read by frames in flight.
  if (gpuModel_) vkDeviceWaitIdle(session_->context().device());
  // Drawn dressed, as every program draws a face (importers/face_dressing.h);
  // dressed here at each upload, as sculpting moves what the occlusion is baked on.
  // A face rigged again from moved landmarks stands in for it (same targets).
  const eng::Model* rerigged = landmarks_.shownInstead(sculpt_.displayModel());
  const eng::Model& shown = rerigged ? *rerigged : sculpt_.displayModel();
  const std::optional<eng::Model> dressed = importers::dressedForDisplay(shown);
  auto gpu = session_->renderer().upload(dressed ? *dressed : shown);
  if (!gpu) return gpu.error();
  gpuModel_.emplace(std::move(*gpu));
  uploadedRevision_ = sculpt_.displayRevision();
  uploadedRigRevision_ = landmarks_.riggedRevision();
  return {};
}

// The face centred in the free middle of the window (between the side panels,
// above the timeline): a lens shift, so orbiting still turns about the face.
eng::OrbitCamera EditorApp::renderCamera() const {
  eng::OrbitCamera camera = view_.camera;
  // The free part shows what `facial play` draws at its size (same camera, same perspective),
  // framed for the window as it is now (it may have been resized).
  camera.viewRegionAsImage(bounds_, {layout_.width, layout_.height}, {layout_.x0(), layout_.top}, {layout_.x1(), layout_.y1()});
  return camera;
}

// The free middle in framebuffer pixels: the panels cover the rest, where the
// renderer then draws nothing of the 3D view.
VkRect2D EditorApp::viewRegionPixels() const {
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  const auto px = [](float v, float s) { return int32_t(std::lround(std::max(v, 0.0f) * s)); };
  const int32_t x0 = px(layout_.x0(), scale.x), y0 = px(layout_.top, scale.y);
  const int32_t x1 = px(layout_.x1(), scale.x), y1 = px(layout_.y1(), scale.y);
  if (x1 <= x0 || y1 <= y0) return {};
  return {{x0, y0}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
}

autorig::PictureCamera EditorApp::pictureCamera() const {
  const eng::OrbitCamera camera = renderCamera();
  return {camera.projection(layout_.width / layout_.height) * camera.view(), {layout_.width, layout_.height}};
}

void EditorApp::rayAt(float px, float py, glm::vec3& origin, glm::vec3& direction) const {
  const eng::OrbitCamera camera = renderCamera();
  const glm::mat4 inverse = glm::inverse(camera.projection(layout_.width / layout_.height) * camera.view());
  const float x = 2.0f * px / layout_.width - 1.0f, y = 2.0f * py / layout_.height - 1.0f;
  glm::vec4 nearPoint = inverse * glm::vec4(x, y, 0.0f, 1.0f), farPoint = inverse * glm::vec4(x, y, 1.0f, 1.0f);
  origin = glm::vec3(nearPoint) / nearPoint.w;
  direction = glm::normalize(glm::vec3(farPoint) / farPoint.w - origin);
}

void EditorApp::handleViewportInput() {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantTextInput && ImGui::IsKeyPressed(GLFW_KEY_F12, false) && pendingShot_.empty()) pendingShot_ = defaultShot_;
  if (!io.WantTextInput && !io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_F, false))
    setFraming(framing_ == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face);
  timeline_->handleShortcuts();
  const bool overViewport = !io.WantCaptureMouse;
  if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && overViewport) {
    if (sculpt_.pickMode()) {
      pickAt(io.MousePos.x, io.MousePos.y);
    } else if (landmarks_.clickAt({io.MousePos.x, io.MousePos.y}, pictureCamera())) {
      landmarkDragging_ = true;
    } else if (io.KeyShift && sculpt_.hasSelection()) {
      sculptDragging_ = true;
    } else {
      orbiting_ = true;
    }
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) orbiting_ = sculptDragging_ = landmarkDragging_ = false;
  if (landmarkDragging_ && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f))
    landmarks_.dragSelected({io.MouseDelta.x, io.MouseDelta.y}, pictureCamera());
  if (orbiting_) orbit(-0.3f * io.MouseDelta.x, 0.3f * io.MouseDelta.y);
  if (sculptDragging_ && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f))
    dragSelectedByPixels(io.MouseDelta.x, io.MouseDelta.y);
  if (overViewport && io.MouseWheel != 0.0f)
    view_.camera.zoom = std::clamp(view_.camera.zoom * std::pow(1.1f, io.MouseWheel), kMinViewZoom, kMaxViewZoom);
}

bool EditorApp::pickAt(float px, float py) {
  glm::vec3 origin, direction;
  rayAt(px, py, origin, direction);
  return sculpt_.pick(origin, direction, faceWeights());
}

bool EditorApp::dragSelectedByPixels(float dx, float dy) {
  // Screen-plane drag: pixels to world units at the face's depth.
  const eng::OrbitCamera camera = renderCamera();
  const float d = camera.distance / std::max(camera.zoom, 1e-3f);
  const float worldPerPixel = 2.0f * d * std::tan(glm::radians(camera.fovYDegrees) * 0.5f) / layout_.height;
  const glm::vec3 forward = glm::normalize(camera.target - camera.position());
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  return sculpt_.dragSelected(worldPerPixel * (dx * right - dy * up));
}

void EditorApp::orbit(float yawDegrees, float pitchDegrees) {
  view_.camera.yawDegrees += yawDegrees;
  view_.camera.pitchDegrees = std::clamp(view_.camera.pitchDegrees + pitchDegrees, -80.0f, 80.0f);
}

// Where the face is drawn and from where: a screenshot compared with another
// program's frame is cropped to this region (the camera is framed into it).
void EditorApp::logView() const {
  std::printf("view: region %.0f,%.0f %.0fx%.0f, yaw %.2f, pitch %.2f, zoom %.4f, %s\n", layout_.x0(), layout_.top,
              layout_.x1() - layout_.x0(), layout_.y1() - layout_.top, view_.camera.yawDegrees, view_.camera.pitchDegrees,
              view_.camera.zoom, framing_ == eng::FramingMode::All ? "whole model" : "face");
}

void EditorApp::logTimeline() const {
  const TimelineDocument& doc = timeline_->document();
  size_t keys = 0;
  for (const DocumentTrack& track : doc.tracks()) keys += track.keys.size();
  std::printf("timeline: %zu tracks, %zu keys, %zu selected, playhead %.3f s%s\n", doc.tracks().size(), keys,
              doc.selection().size(), timeline_->playhead(), doc.dirty() ? ", modified" : "");
}

bool EditorApp::runAction(const EditorScriptAction& a) {
  using Kind = EditorScriptAction::Kind;
  switch (a.kind) {
    case Kind::Trigger: return machine_.pressTrigger(a.text, *this);
    case Kind::Pad:
      controlMap_.dragCursor({a.a, a.b}, *this);
      showPadTab_ = 0;  // as clicking the Control map tab first
      return true;
    case Kind::Orbit: orbit(a.a, a.b); return true;
    case Kind::Zoom: view_.camera.zoom = std::clamp(a.a, kMinViewZoom, kMaxViewZoom); return true;
    case Kind::TimelineOpen: return timeline_->open(a.text);
    case Kind::TimelineSeek: timeline_->seek(a.a, *this); return true;
    case Kind::TimelineKeyAll: return timeline_->keyAll(*this);
    case Kind::TimelineKey: return timeline_->selectTrack(a.text) && timeline_->keyTrack(*this);
    case Kind::TimelineMoveSelected: return timeline_->moveSelected(a.a, a.b, *this);
    case Kind::TimelineDelete: return timeline_->deleteSelected();
    case Kind::Undo: return timeline_->undo();
    case Kind::Redo: return timeline_->redo();
    case Kind::TimelineSave: return timeline_->save(a.text);
    case Kind::SculptPick:
      sculpt_.setPickMode(true);  // as ticking "Pick points on the face" before the click
      return pickAt(a.a, a.b);
    case Kind::SculptLandmark: return sculpt_.pressAddLandmark(a.text);
    case Kind::SculptMove: return sculpt_.dragSelected({a.a, a.b, a.c});
    case Kind::SculptDrag:
      sculpt_.setPickMode(false);  // Shift+drag moves points only outside pick mode
      return dragSelectedByPixels(a.a, a.b);
    case Kind::SculptKernel: {
      const facial::RbfKernelType type = a.text == "biharmonic"     ? facial::RbfKernelType::Biharmonic
                                         : a.text == "polyharmonic" ? facial::RbfKernelType::Polyharmonic
                                                                    : facial::RbfKernelType::Multiquadric;
      return sculpt_.chooseKernel(type, a.hasNumber ? a.a : 0.0f);
    }
    case Kind::SculptFalloff: return sculpt_.chooseFalloff(a.a);
    case Kind::SculptBake: return sculpt_.pressBake(a.text);
    case Kind::SculptSave: return sculpt_.pressSave(a.text);
    case Kind::LandmarksShow: return landmarks_.pressShow(*setup_);
    case Kind::LandmarkMove: return landmarks_.selectAndMove(int(a.a), {a.b, a.c}, pictureCamera());
    case Kind::AutorigRerun: return landmarks_.pressRerun(*setup_);
    case Kind::LandmarksSave: return landmarks_.pressSave();
    case Kind::Say:
      machine_.setSpeechText(a.text);
      return machine_.pressSpeak(*this);
    case Kind::SayLanguage: machine_.setSpeechLanguage(a.text); return true;
    case Kind::SayStop: machine_.pressStopSpeaking(); return true;
    case Kind::Screenshot:
      pendingShot_ = a.text.empty() ? defaultShot_ : fs::path(a.text);
      logView();
      return true;
    case Kind::Quit: quitRequested_ = true; return true;
    // Dope sheet and curve view (issue 34): the timeline panel runs its own.
    case Kind::TimelineBoxSelect: case Kind::TimelineCopy: case Kind::TimelinePaste: case Kind::TimelineDuplicate:
    case Kind::TimelineNudge: case Kind::TimelineSnap: case Kind::TimelineLoop: case Kind::TimelineSpeed:
    case Kind::TimelineMute: case Kind::TimelineSolo: case Kind::CurveTangent: case Kind::TimelineKeyEmotion:
    case Kind::TimelinePlay: case Kind::TimelinePause:
      return timeline_->runScriptAction(a, *this);
    case Kind::ProjectNew: case Kind::ProjectOpen: case Kind::ProjectSave: case Kind::ProjectSaveAs:
    case Kind::ExportGlb: case Kind::ExportGif: case Kind::ExportVideo: case Kind::QuitDiscard: case Kind::QuitSave:
      return runProjectAction(a);
    default: return runGraphOrPadAction(a);
  }
  return false;
}

// ---------------------------------------------------------------------------
// The state machine diagram, the bilinear pad and Record (issue 34, points 3 and 4).

bool EditorApp::runGraphOrPadAction(const EditorScriptAction& a) {
  using Kind = EditorScriptAction::Kind;
  const auto& w = a.words;
  if (a.kind >= Kind::GraphAddState && a.kind <= Kind::GraphEditTransition) machine_.showDiagram();
  switch (a.kind) {
    case Kind::GraphAddState: return machine_.addState(w[0], w.size() > 1 ? w[1] : w[0]);
    case Kind::GraphRemoveState: return machine_.removeState(w[0]);
    case Kind::GraphRenameState: return machine_.renameState(w[0], w[1]);
    case Kind::GraphAddTransition: return machine_.addTransition(w[0], w[1], w[2], a.a, w[3]);
    case Kind::GraphEditTransition:
      return machine_.editTransition(w[0], w[1], a.a, w[2], std::isnan(a.b) ? std::nullopt : std::optional<float>(a.b), a.c != 0.0f);
    case Kind::GraphSave: return machine_.saveGraph(a.text);
    case Kind::BilinearPad:
      bilinearPad_.dragTo(a.a, a.b, *this);
      showPadTab_ = 1;
      return true;
    case Kind::RecordStart: return startRecording();
    case Kind::RecordStop: return stopRecording();
    default: return false;
  }
}

bool EditorApp::startRecording() {
  if (source_ == FaceSource::Timeline) {
    fail("record: the timeline drives the face; move a pad or a slider to record it");
    return false;
  }
  std::vector<std::string> channels;
  for (uint32_t i = 0; i < facial::rigInputCount(); ++i) channels.emplace_back(facial::rigInputName(i));
  recordValues_.assign(channels.size(), 0.0f);
  recordElapsed_ = 0.0f;
  recorder_.start(std::move(channels), timeline_->playhead());
  sampleRecording(0.0f);
  std::printf("record: started at %.3f s\n", timeline_->playhead());
  std::fflush(stdout);
  return true;
}

void EditorApp::sampleRecording(float dt) {
  if (!recorder_.recording()) return;
  recordElapsed_ += dt;
  for (size_t c = 0; c < recordValues_.size(); ++c) recordValues_[c] = currentValue(recorder_.channels()[c]);
  recorder_.sample(recordElapsed_, recordValues_);
}

bool EditorApp::stopRecording() {
  if (!recorder_.recording()) return false;
  const size_t samples = recorder_.sampleCount();
  const std::vector<RecordedTrack> tracks = recorder_.stop();
  auto written = writeRecording(timeline_->document(), tracks, samples);
  if (!written) {
    fail("record: " + written.error().message);
    return false;
  }
  std::printf("record: %zu tracks, %zu keys from %zu frames over %.2f s\n", written->tracks, written->keys, written->samples,
              written->seconds);
  logTimeline();
  return true;
}

void EditorApp::drawPadWindow() {
  if (ImGui::Button(recorder_.recording() ? "Stop recording" : "Record")) {
    if (recorder_.recording())
      stopRecording();
    else
      startRecording();
  }
  tooltip("Writes what the pads and sliders do into the timeline as keys, from the playhead (a few keys a second)");
  if (ImGui::BeginTabBar("pads")) {
    const auto tabFlags = [&](int tab) { return showPadTab_ == tab ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None; };
    const bool controlMap = ImGui::BeginTabItem("Control map", nullptr, tabFlags(0));
    tooltip("The study's control map (four poles) or the freeform map (six): drag its cursor");
    if (controlMap) {
      controlMap_.draw(*this);
      ImGui::EndTabItem();
    }
    const bool bilinear = ImGui::BeginTabItem("Bilinear pad", nullptr, tabFlags(1));
    tooltip("Four expressions at the corners, blended bilinearly (s, t): drag its cursor");
    if (bilinear) {
      bilinearPad_.draw(*this);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
    showPadTab_ = -1;
  }
}

void EditorApp::runScript(float elapsed) {
  // A screenshot waits for its frame: it shows everything scripted before it
  // and nothing after, however slow the frames.
  for (; nextAction_ < script_.size() && script_[nextAction_].time <= elapsed && pendingShot_.empty() && !quitRequested_;
       ++nextAction_) {
    const EditorScriptAction& a = script_[nextAction_];
    std::printf("script %.2f s: %s\n", a.time, a.written.c_str());
    std::fflush(stdout);
    if (!runAction(a)) {
      ++failedActions_;
      fail(a.source + ": failed (see above)");
    }
    const int k = int(a.kind);
    if (k >= int(EditorScriptAction::Kind::TimelineOpen) && k <= int(EditorScriptAction::Kind::TimelineSave)) logTimeline();
    if (k >= int(EditorScriptAction::Kind::GraphAddState) && k <= int(EditorScriptAction::Kind::GraphSave) && machine_.document())
      std::printf("graph: %zu states, %zu transitions%s\n", machine_.document()->states().size(),
                  machine_.document()->transitions().size(), machine_.document()->dirty() ? ", modified" : "");
    if (k >= int(EditorScriptAction::Kind::TimelineBoxSelect) && k <= int(EditorScriptAction::Kind::TimelinePause)) logTimeline();
    if ((a.kind == EditorScriptAction::Kind::SculptMove || a.kind == EditorScriptAction::Kind::SculptDrag) && sculpt_.hasSelection()) {
      const SculptPoint& p = sculpt_.points()[size_t(sculpt_.selected())];
      std::printf("sculpt: '%s' displaced by (%.5f, %.5f, %.5f)\n", p.name.c_str(), p.displacement.x, p.displacement.y,
                  p.displacement.z);
    }
  }
}

void EditorApp::drawControlPoints() {
  if (sculpt_.points().empty()) return;
  sculpt_.pointsOnFace(faceWeights(), pointsOnFace_, pointsMoved_);
  const eng::OrbitCamera camera = renderCamera();
  const glm::mat4 clip = camera.projection(layout_.width / layout_.height) * camera.view();
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const auto toScreen = [&](const glm::vec3& p, ImVec2& out) {
    const glm::vec4 c = clip * glm::vec4(p, 1.0f);
    if (c.w <= 0.0f) return false;
    out = {(c.x / c.w * 0.5f + 0.5f) * layout_.width, (c.y / c.w * 0.5f + 0.5f) * layout_.height};
    return true;
  };
  // A dark rim keeps the markers readable on light skin.
  const ImU32 rim = IM_COL32(20, 24, 32, 220);
  for (size_t i = 0; i < pointsOnFace_.size(); ++i) {
    ImVec2 rest, moved;
    if (!toScreen(pointsOnFace_[i], rest) || !toScreen(pointsMoved_[i], moved)) continue;
    const bool selected = int(i) == sculpt_.selected();
    const ImU32 colour = selected ? IM_COL32(255, 180, 60, 255) : IM_COL32(90, 200, 255, 255);
    const float radius = selected ? 5.0f : 4.0f;
    draw->AddLine(rest, moved, rim, 3.5f);
    draw->AddLine(rest, moved, colour, 1.5f);
    draw->AddCircle(rest, 3.5f, rim, 12, 2.5f);
    draw->AddCircle(rest, 3.5f, colour, 12, 1.2f);
    draw->AddCircleFilled(moved, radius + 1.5f, rim, 16);
    draw->AddCircleFilled(moved, radius, colour, 16);
  }
}

// The docked panels' background as ImGui would blend its WindowBg over the
// renderer's fill (in linear light: the window is sRGB), given to the
// renderer as that fill so the panels draw none: on a CPU device blending a
// background over two thirds of the window cost about 2 ms a frame.
glm::vec3 EditorApp::panelBackground() const {
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  const glm::vec3 under = 0.5f * (view_.lights.backgroundTop + view_.lights.backgroundBottom);
  return glm::vec3(bg.x, bg.y, bg.z) * bg.w + under * (1.0f - bg.w);
}

void EditorApp::drawPanels() {
  // Their background is the renderer's fill around the 3D view (panelBackground()).
  const ImGuiWindowFlags docked =
      ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBackground;
  const Layout& l = layout_;
  ImGui::SetNextWindowPos({0, l.top}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({l.side, l.leftSplit - l.top}, ImGuiCond_Always);
  ImGui::Begin("State machine", nullptr, docked);
  machine_.draw(*this);
  ImGui::End();

  ImGui::SetNextWindowPos({0, l.leftSplit}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({l.side, l.height - l.bottom - l.leftSplit}, ImGuiCond_Always);
  ImGui::Begin("Control map", nullptr, docked);
  drawPadWindow();
  ImGui::End();
  machine_.drawDiagramWindow({l.x0() + 10.0f, 30.0f}, {std::min(l.x1() - l.x0() - 20.0f, 620.0f), std::min(l.y1() - 60.0f, 400.0f)});

  ImGui::SetNextWindowPos({l.width - l.side, l.top}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({l.side, l.height - l.bottom - l.top}, ImGuiCond_Always);
  ImGui::Begin("RBF sculpt", nullptr, docked);
  sculpt_.draw();
  const bool landmarksOpen = ImGui::CollapsingHeader("Landmarks (autorig)");
  tooltip("The 68 face landmarks the targets were rigged from: show, move and rig again");
  if (landmarksOpen) landmarks_.draw(*setup_);
  ImGui::End();

  ImGui::SetNextWindowPos({0, l.height - l.bottom}, ImGuiCond_Always);
  ImGui::SetNextWindowSize({l.width, l.bottom}, ImGuiCond_Always);
  ImGui::Begin("Timeline", nullptr, docked);
  timeline_->draw(*this);
  ImGui::End();

  landmarks_.drawOverlay(ImGui::GetBackgroundDrawList(), pictureCamera());

  // Status over the viewport's top edge.
  char status[160];
  std::snprintf(status, sizeof status, "%s  |  face from: %s  |  %.1f ms%s", setup_->name().c_str(), faceSourceName(source_), frameMs_,
                recorder_.recording() ? "  |  REC" : "");
  ImGui::GetBackgroundDrawList()->AddText({l.x0() + 10.0f, l.top + 8.0f}, IM_COL32(230, 230, 235, 255), status);
  if (!project_->message().text.empty())
    ImGui::GetBackgroundDrawList()->AddText({l.x0() + 10.0f, l.top + 26.0f},
                                            project_->message().error ? IM_COL32(255, 120, 100, 255) : IM_COL32(150, 215, 150, 255),
                                            project_->message().text.c_str());
  ImGui::GetBackgroundDrawList()->AddText({l.x0() + 10.0f, l.y1() - 22.0f}, IM_COL32(170, 170, 180, 255),
                                          "drag: orbit   wheel: zoom   F12: screenshot   Ctrl+Z/Y: undo/redo");
}

// --- Projects, export and the menu bar (issue 34, points 5-7) ---

ProjectView EditorApp::viewSettings() const {
  return {.yawDegrees = view_.camera.yawDegrees,
          .pitchDegrees = view_.camera.pitchDegrees,
          .zoom = view_.camera.zoom,
          .wholeModel = framing_ == eng::FramingMode::All};
}

void EditorApp::applyViewSettings(const ProjectView& view) {
  setFraming(view.wholeModel ? eng::FramingMode::All : eng::FramingMode::Face);
  view_.camera.yawDegrees = view.yawDegrees;
  view_.camera.pitchDegrees = std::clamp(view.pitchDegrees, -80.0f, 80.0f);
  view_.camera.zoom = std::clamp(view.zoom, kMinViewZoom, kMaxViewZoom);
}

void EditorApp::setFraming(eng::FramingMode framing) {
  // renderCamera() frames bounds_ each frame; the orbit target follows it.
  framing_ = framing;
  bounds_ = eng::framingBounds(setup_->model(), framing_);
  view_.camera.target = eng::OrbitCamera::frame(bounds_, 1.0f).target;
}

bool EditorApp::runProjectAction(const EditorScriptAction& a) {
  using Kind = EditorScriptAction::Kind;
  switch (a.kind) {
    case Kind::ProjectNew: return project_->newProject();
    case Kind::ProjectOpen: return openProject(a.text, nextAction_ + 1, a.time);
    case Kind::ProjectSave: return a.text.empty() ? project_->save() : project_->saveAs(a.text);
    case Kind::ProjectSaveAs: return project_->saveAs(a.text);
    case Kind::ExportGlb: return project_->exportGlb(a.text);
    case Kind::ExportGif: return project_->exportGif(a.text, a.words.size() > 1 ? a.words[1] : std::string());
    case Kind::ExportVideo: return project_->exportVideo(a.text, a.words.size() > 1 ? a.words[1] : std::string());
    case Kind::QuitDiscard:
      project_->discardUnsaved();
      quitDiscarded_ = quitRequested_ = true;
      return true;
    case Kind::QuitSave: {
      // Quits even when the save fails (a script must not hang on the question); the changes stay in the autosaves.
      const bool saved = project_->save();
      quitRequested_ = true;
      return saved;
    }
    default: return false;
  }
}

void EditorApp::runMenuRequest(const MenuRequest& request) {
  const fs::path path = request.path;
  switch (request.command) {
    case MenuCommand::None: return;
    case MenuCommand::New: project_->newProject(); return;
    case MenuCommand::Open: openProject(path, nextAction_, 0.0f); return;
    case MenuCommand::Save: project_->save(); return;
    case MenuCommand::SaveAs: project_->saveAs(path); return;
    case MenuCommand::ExportGlb: project_->exportGlb(path); return;
    case MenuCommand::ExportGif: project_->exportGif(path, ""); return;
    case MenuCommand::ExportVideo: project_->exportVideo(path, ""); return;
    case MenuCommand::Quit: quitRequested_ = true; return;
    case MenuCommand::QuitSave: quitRequested_ = path.empty() ? project_->save() : project_->saveAs(path); return;
    case MenuCommand::QuitDiscard:
      project_->discardUnsaved();
      quitDiscarded_ = quitRequested_ = true;
      return;
    case MenuCommand::Undo: timeline_->undo(); return;
    case MenuCommand::Redo: timeline_->redo(); return;
    case MenuCommand::Copy: timeline_->copySelection(); return;
    case MenuCommand::Paste: timeline_->pasteAt(timeline_->playhead()); return;
    case MenuCommand::Duplicate: timeline_->duplicateSelection(); return;
    case MenuCommand::SelectAll: timeline_->selectAll(); return;
    case MenuCommand::ToggleFraming: setFraming(framing_ == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face); return;
    case MenuCommand::Screenshot:
      if (pendingShot_.empty()) pendingShot_ = defaultShot_;
      return;
  }
}

bool EditorApp::openProject(const fs::path& path, size_t scriptNext, float scriptTime) {
  if (!project_->madeOnAnotherFace(path)) return project_->open(path);
  // The face is loaded once per editor: this one closes (its unsaved changes
  // stay in the autosaves) and runEditor starts one on the project's face.
  std::printf("facial-editor: %s was made on another face: reopening the editor on it\n", path.string().c_str());
  reopen = path;
  reopenScriptFrom = scriptNext;
  reopenClock = scriptTime;
  quitRequested_ = true;
  return true;
}

void EditorApp::updateProjectAndTitle() {
  project_->update(std::chrono::steady_clock::now());
  std::string title = project_->windowTitle();
  if (title == title_) return;
  title_ = std::move(title);
  glfwSetWindowTitle(session_->window().handle(), title_.c_str());
}

// The window's close button: with unsaved changes the window stays and the question is asked.
void EditorApp::onWindowClose(GLFWwindow* window) {
  if (!gEditor || !gEditor->project_ || !gEditor->project_->dirty()) return;
  glfwSetWindowShouldClose(window, GLFW_FALSE);
  gEditor->menu_.askToQuit();
}

int EditorApp::run(const EditorOptions& o) {
  if (const int error = setUp(o); error != 0) return error;
  int exitCode = 0;
  auto frame = [&](const app::WindowTick& tick) -> eng::Result<app::WindowFramePlan> {
    frameMs_ = frameMs_ == 0.0f ? 1000.0f * tick.dt : 0.9f * frameMs_ + 0.1f * 1000.0f * tick.dt;
    const VkExtent2D extent = session_->renderer().extent();
    layout_ = Layout::of(float(std::max(extent.width, 1u)), float(std::max(extent.height, 1u)), menu_.height());
    session_->ui().beginFrame();
    runMenuRequest(menu_.draw({.recent = &project_->recent().paths(),
                               .hasProjectFile = !project_->path().empty(),
                               .dirty = project_->dirty(),
                               .canUndo = timeline_->document().canUndo(),
                               .canRedo = timeline_->document().canRedo(),
                               .hasSelection = !timeline_->document().selection().empty(),
                               .hasClipboard = timeline_->hasClipboard()}));
    handleViewportInput();
    runScript(tick.animationTime);
    machine_.update(tick.dt);
    controlMap_.update(tick.dt);
    bilinearPad_.update();
    timeline_->update(tick.dt);
    sampleRecording(tick.dt);
    drawPanels();
    drawControlPoints();
    session_->ui().endFrame();
    updateProjectAndTitle();

    if (auto uploaded = uploadDisplayModel(); !uploaded) return uploaded.error();
    sculpt_.displayWeights(faceWeights(), displayWeights_);
    // Sizes were fixed at set-up and the weights come clamped from the rig: cannot fail.
    (void)materials_.update(faceExpressionWeights());
    instance_ = {&*gpuModel_, glm::mat4(1.0f), displayWeights_, {}, materials_.materials()};
    app::WindowFramePlan plan{.input = {view_, {&instance_, 1}}, .requestedShot = pendingShot_, .quit = quitRequested_};
    plan.input.view.camera = renderCamera();
    plan.input.viewRegion = viewRegionPixels();
    plan.input.surroundColour = panelBackground();
    plan.input.overlay = eng::vk::ImGuiLayer::recorder();
    return plan;
  };
  auto shotWritten = [&](const fs::path& shot) {
    if (shot == pendingShot_) pendingShot_.clear();
  };
  if (auto ran = app::runWindowLoop(session_->window(), session_->renderer(), {.quitAfter = o.quitAfter, .finalScreenshot = o.screenshot, .profile = o.profile},
                                    frame, shotWritten);
      !ran) {
    // The window cannot draw any more (a lost device, say): the user's edits
    // go to the autosave before anything else can fail, and the one error
    // line says where they are.
    project_->keepUnsaved();
    const std::string kept = timeline_->keepUnsavedEdits();
    exitCode = fail(ran.error().message + (kept.empty() ? "" : "; " + kept));
  }
  gEditor = nullptr;  // the window's callbacks are done
  if (!quitDiscarded_) project_->keepUnsaved();  // a plain quit keeps unsaved changes in the autosaves
  std::printf("facial-editor: %s, face from %s, state %s, %zu timeline tracks, %zu sculpt points, %.1f ms/frame\n",
              setup_->name().c_str(), faceSourceName(source_), machine_.currentState().c_str(),
              timeline_->document().tracks().size(), sculpt_.points().size(), frameMs_);
  if (auto clean = session_->finish(); !clean) return fail(clean.error().message);
  if (nextAction_ < script_.size() && exitCode == 0 && reopen.empty())
    std::printf("facial-editor: closed before %zu scripted action(s) ran\n", script_.size() - nextAction_);
  if (failedActions_ > 0 && exitCode == 0)
    return fail(std::to_string(failedActions_) + " scripted action(s) failed (" + o.script + ")");
  return exitCode;
}

}  // namespace

int runEditor(const EditorOptions& options) {
  EditorOptions o = options;
  for (;;) {
    if (!o.project.empty()) {
      // The project's face, rig map and graph are what the editor loads (an autosave keeps the same ones).
      auto project = loadProject(o.project);
      if (!project) return fail(project.error().message);
      o.model = project->model.string();
      o.rigmap = project->rigmap.string();
      o.graph = project->graph.string();
    }
    EditorApp app;
    const int code = app.run(o);
    if (code != 0 || app.reopen.empty()) return code;
    // A project on another face: the next editor opens it and goes on with the script.
    o.project = app.reopen.string();
    o.scriptFrom += app.reopenScriptFrom;
    o.scriptClockFrom += app.reopenClock;
    if (o.quitAfter > 0.0f) o.quitAfter = std::max(0.1f, o.quitAfter - app.reopenClock);
    o.trigger.clear();
    o.timeline.clear();
  }
}

}  // namespace editor
