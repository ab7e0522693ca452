#include "editor/app/state_machine_panel.h"
#include "editor/app/tooltip.h"

#include <imgui.h>

#include <cstdio>
#include <cstring>

#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace editor {

namespace {

// "emotions" when it is a state machine, else the first state machine node.
std::optional<facial::NodeIndex> findStateMachine(const facial::GraphDefinition& graph) {
  if (auto node = graph.findNode("emotions"); node && graph.nodeAs<facial::StateMachineNode>(*node)) return node;
  for (facial::NodeIndex n = 0; n < graph.nodes().size(); ++n)
    if (graph.nodeAs<facial::StateMachineNode>(n)) return n;
  return std::nullopt;
}

}  // namespace

eng::Result<void> StateMachinePanel::load(const app::FaceSetup& face, const std::string& graphPath) {
  face_ = &face;
  auto graph = facial::loadGraph(graphPath, {.presets = facial::presetLookup(face.expressions())});
  if (!graph) return graph.error();
  ENG_TRY(adopt(std::move(*graph), graphPath));
  // A graph without a state machine runs; it just has no diagram to edit.
  auto document = GraphDocument::load(graphPath);
  document_.reset();
  if (document) document_.emplace(std::move(*document));
  selectedState_ = selectedTransition_ = -1;
  return {};
}

eng::Result<void> StateMachinePanel::adopt(facial::SharedGraphDefinition graph, const std::string& graphPath) {
  const std::vector<std::string> names = face_->layout().names();
  auto driver = facial::FaceDriver::create(graph, &face_->graphRig(), names, face_->baseWeights(), 1);
  if (!driver) return driver.error().prefixed(graphPath + ": ");
  // The editor drives the machine by hand: a graph's autoplay switch starts off.
  if (const auto autoplay = graph->findParameter("autoplay");
      autoplay && graph->parameters()[*autoplay].type == facial::ParameterType::Bool)
    driver->graph().setBool(*autoplay, false);
  driver_.emplace(std::move(*driver));
  machine_ = findStateMachine(*graph);
  loadedPath_ = graphPath;
  std::snprintf(pathInput_, sizeof pathInput_, "%s", graphPath.c_str());
  driver_->update(0.0f);
  return {};
}

void StateMachinePanel::update(float dt) {
  if (!driver_) return;
  // The mouth at the time of the sample being heard (the audio clock, not the frame clock).
  const std::optional<float> time = speech_.update();
  if (time) {
    speechTime_ = *time;
  } else if (speechShown_) {
    speechShown_ = false;
    std::printf("facial-editor: speech: done\n");
    std::fflush(stdout);
  }
  driver_->setSpeech(speech_.track(), speechTime_);  // the player's clock is finite
  driver_->update(dt);
}

bool StateMachinePanel::pressSpeak(FaceDelegate& face) {
  if (!driver_) return false;
  if (!face_->graphRig().speaks()) {
    message_.report(facial::cannotSpeakMessage(face_->graphRig(), face_->name()), true);
    return false;
  }
  auto track = speech_.start(speechBox_.text(), speechBox_.language());
  if (!track) {
    speechBox_.reportProblem("facial-editor", track.error().message);
    return false;
  }
  face.takeControl(FaceSource::StateMachine);
  speechTime_ = 0.0f;
  speechShown_ = true;
  speechBox_.reportStarted("facial-editor", speech_.describe(), speech_.takeNotes());
  return true;
}

void StateMachinePanel::pressStopSpeaking() {
  if (!speech_.speaking()) return;
  speech_.stop();
  speechShown_ = false;
  std::printf("facial-editor: speech: stopped\n");
  std::fflush(stdout);
}

std::string StateMachinePanel::currentState() const {
  if (!driver_ || !machine_) return {};
  const auto status = driver_->graph().stateMachineStatus(*machine_);
  const auto* node = driver_->graph().definition().nodeAs<facial::StateMachineNode>(*machine_);
  if (!status || !node || status->current >= node->states.size()) return {};
  return node->states[status->current].name;
}

bool StateMachinePanel::hasTrigger(std::string_view trigger) const {
  if (!driver_) return false;
  const auto p = driver_->graph().definition().findParameter(trigger);
  return p && driver_->graph().definition().parameters()[*p].type == facial::ParameterType::Trigger;
}

bool StateMachinePanel::pressTrigger(std::string_view trigger, FaceDelegate& face) {
  if (!fire(trigger)) return false;
  face.takeControl(FaceSource::StateMachine);
  return true;
}

bool StateMachinePanel::fire(std::string_view trigger) {
  if (!hasTrigger(trigger)) return false;
  return driver_->graph().setTrigger(*driver_->graph().definition().findParameter(trigger));
}

void StateMachinePanel::draw(FaceDelegate& face) {
  ImGui::SetNextItemWidth(-70.0f);
  ImGui::InputText("##graph", pathInput_, sizeof pathInput_);
  tooltip("A graph file (data/graphs/*.json), relative to the folder the editor was started in");
  ImGui::SameLine();
  const bool loadPressed = ImGui::Button("Load##graph");
  tooltip("Load the graph and run it on the face (the one running stays when it does not load)");
  if (loadPressed) {
    const std::string path = pathInput_;
    auto previous = std::move(driver_);
    if (auto loaded = load(*face_, path); loaded) {
      message_.report("graph loaded: " + path, false);
    } else {
      driver_ = std::move(previous);
      std::snprintf(pathInput_, sizeof pathInput_, "%s", loadedPath_.c_str());
      message_.report(loaded.error().message, true);
    }
  }
  message_.draw();
  if (!driver_) return;
  if (document_) {
    ImGui::Checkbox("diagram (edit the state machine)", &diagramShown_);
    tooltip("States as boxes, transitions as arrows: add, rename, remove, edit timing; Save writes the graph file");
  }
  facial::GraphInstance& graph = driver_->graph();
  const facial::GraphDefinition& definition = graph.definition();

  const bool driving = face.source() == FaceSource::StateMachine;
  if (!driving && ImGui::Button("Drive the face from this graph")) face.takeControl(FaceSource::StateMachine);
  if (!driving) tooltip("Give the face back to the state machine (a pad or the timeline drives it now)");
  if (driving) ImGui::TextColored({0.55f, 0.85f, 1.0f, 1.0f}, "drives the face");

  if (machine_) {
    const auto status = graph.stateMachineStatus(*machine_);
    const auto* node = definition.nodeAs<facial::StateMachineNode>(*machine_);
    if (status && node) {
      ImGui::Text("state: %s  (%.1f s)", node->states[status->current].name.c_str(), status->stateTime);
      char overlay[96];
      if (status->blending) {
        const char* from = status->liveSource && *status->liveSource < node->states.size()
                               ? node->states[*status->liveSource].name.c_str()
                               : "snapshot";
        std::snprintf(overlay, sizeof overlay, "%s -> %s  %.0f%%", from, node->states[status->current].name.c_str(),
                      100.0f * status->blendProgress);
      } else {
        std::snprintf(overlay, sizeof overlay, "settled");
      }
      ImGui::ProgressBar(status->blending ? status->blendProgress : 1.0f, {-1.0f, 0.0f}, overlay);
    }
  } else {
    ImGui::TextDisabled("this graph has no state machine");
  }

  ImGui::Separator();
  ImGui::TextDisabled("triggers");
  int shown = 0;
  for (facial::ParameterIndex p = 0; p < definition.parameters().size(); ++p) {
    const facial::ParameterDecl& decl = definition.parameters()[p];
    if (decl.type != facial::ParameterType::Trigger) continue;
    if (shown++ % 3 != 0) ImGui::SameLine();
    ImGui::PushID(int(p));
    if (ImGui::Button(decl.name.c_str(), {92.0f, 0.0f})) pressTrigger(decl.name, face);
    tooltip("Fire this trigger: the state machine takes the transition it starts");
    ImGui::PopID();
  }
  ImGui::Separator();
  ImGui::TextDisabled("speak (under the current emotion)");
  switch (speechBox_.draw({.speaking = speech_.speaking(), .time = speechTime_, .seconds = float(speech_.lineSeconds())},
                          ImGui::GetContentRegionAvail().x)) {
    case app::SpeechBox::Action::Speak: pressSpeak(face); break;
    case app::SpeechBox::Action::Stop: pressStopSpeaking(); break;
    case app::SpeechBox::Action::None: break;
  }
  drawParameters();
}

// The graph's float and bool parameters as sliders and check boxes.
void StateMachinePanel::drawParameters() {
  facial::GraphInstance& graph = driver_->graph();
  const facial::GraphDefinition& definition = graph.definition();
  ImGui::Separator();
  ImGui::TextDisabled("parameters");
  for (facial::ParameterIndex p = 0; p < definition.parameters().size(); ++p) {
    const facial::ParameterDecl& decl = definition.parameters()[p];
    ImGui::PushID(int(p));
    if (decl.type == facial::ParameterType::Float) {
      float value = graph.parameters()[p];
      if (ImGui::SliderFloat(decl.name.c_str(), &value, 0.0f, 1.0f)) graph.setFloat(p, value);
      tooltip("A float parameter of the graph (Ctrl+click to type a value)");
    } else if (decl.type == facial::ParameterType::Bool) {
      bool value = graph.parameters()[p] != 0.0f;
      if (ImGui::Checkbox(decl.name.c_str(), &value)) graph.setBool(p, value);
      tooltip("A bool parameter of the graph (conditions of transitions read it)");
    }
    ImGui::PopID();
  }
}

}  // namespace editor
