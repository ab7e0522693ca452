// The state machine panel's diagram window and its edits (state_machine_panel.h).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "editor/app/tooltip.h"
#include "editor/app/state_machine_panel.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace editor {

namespace {

constexpr const char* kEasings[] = {"linear", "cosine", "smoothstep"};

ImVec2 screen(glm::vec2 origin, glm::vec2 p) { return {origin.x + p.x, origin.y + p.y}; }

void drawArrowHead(ImDrawList* draw, ImVec2 from, ImVec2 to, ImU32 colour) {
  const glm::vec2 d = glm::normalize(glm::vec2(to.x - from.x, to.y - from.y)), side{-d.y, d.x};
  const glm::vec2 tip{to.x, to.y}, back = tip - 9.0f * d;
  draw->AddTriangleFilled(to, {back.x + 4.0f * side.x, back.y + 4.0f * side.y}, {back.x - 4.0f * side.x, back.y - 4.0f * side.y},
                          colour);
}

}  // namespace

bool StateMachinePanel::rebuildFromDocument() {
  auto graph = facial::parseGraph(document_->json(), loadedPath_, {.presets = facial::presetLookup(face_->expressions())});
  if (!graph) {
    message_.report(graph.error().message, true);
    return false;
  }
  if (auto adopted = adopt(std::move(*graph), loadedPath_); !adopted) {
    message_.report(adopted.error().message, true);
    return false;
  }
  return true;
}

bool StateMachinePanel::applyEdit(const eng::Result<void>& edited, const std::string& what) {
  if (!edited) {
    message_.report(what + ": " + edited.error().message, true);
    return false;
  }
  if (!rebuildFromDocument()) {
    document_->discardLast();  // the runtime refused it: the running graph stays as it was
    return false;
  }
  selectedState_ = std::min(selectedState_, int(document_->states().size()) - 1);
  selectedTransition_ = std::min(selectedTransition_, int(document_->transitions().size()) - 1);
  message_.report("graph: " + what, false);
  return true;
}

bool StateMachinePanel::addState(std::string_view name, std::string_view expression) {
  if (!document_) return false;
  return applyEdit(document_->addState(name, expression), "added state " + std::string(name) + " (" + std::string(expression) + ")");
}

bool StateMachinePanel::removeState(std::string_view name) {
  if (!document_) return false;
  return applyEdit(document_->removeState(name), "removed state " + std::string(name));
}

bool StateMachinePanel::renameState(std::string_view from, std::string_view to) {
  if (!document_) return false;
  return applyEdit(document_->renameState(from, to), "renamed state " + std::string(from) + " to " + std::string(to));
}

bool StateMachinePanel::addTransition(std::string_view from, std::string_view to, std::string_view trigger, float duration,
                                      std::string_view easing) {
  if (!document_) return false;
  return applyEdit(document_->addTransition(from, to, trigger, duration, easing),
                   "added transition " + std::string(from) + " -> " + std::string(to));
}

bool StateMachinePanel::editTransition(std::string_view from, std::string_view to, float duration, std::string_view easing,
                                       std::optional<float> exitTime, bool interruptible) {
  if (!document_) return false;
  return applyEdit(document_->editTransition(from, to, duration, easing, exitTime, interruptible),
                   "edited transition " + std::string(from) + " -> " + std::string(to));
}

bool StateMachinePanel::removeTransition(std::string_view from, std::string_view to) {
  if (!document_) return false;
  return applyEdit(document_->removeTransition(from, to), "removed transition " + std::string(from) + " -> " + std::string(to));
}

bool StateMachinePanel::undoGraphEdit() {
  if (!document_ || !document_->undo()) return false;
  if (!rebuildFromDocument()) document_->redo();
  return true;
}

bool StateMachinePanel::redoGraphEdit() {
  if (!document_ || !document_->redo()) return false;
  if (!rebuildFromDocument()) document_->undo();
  return true;
}

bool StateMachinePanel::saveGraph(const std::string& path) {
  if (!document_) {
    message_.report("this graph has no state machine to save from the diagram", true);
    return false;
  }
  if (auto saved = document_->save(path); !saved) {
    message_.report(saved.error().message, true);
    return false;
  }
  message_.report("graph saved: " + path, false);
  return true;
}

void StateMachinePanel::drawDiagramWindow(glm::vec2 at, glm::vec2 size) {
  if (!document_ || !diagramShown_) return;
  ImGui::SetNextWindowPos({at.x, at.y}, ImGuiCond_Appearing);
  ImGui::SetNextWindowSize({size.x, size.y}, ImGuiCond_Appearing);
  if (ImGui::Begin("State machine diagram", &diagramShown_)) {
    if (ImGui::BeginTable("diagram", 2, ImGuiTableFlags_Resizable)) {
      ImGui::TableSetupColumn("canvas", ImGuiTableColumnFlags_WidthStretch, 3.0f);
      ImGui::TableSetupColumn("edit", ImGuiTableColumnFlags_WidthStretch, 1.4f);
      ImGui::TableNextColumn();
      drawDiagramCanvas();
      ImGui::TableNextColumn();
      drawStateEditor();
      drawTransitionEditor();
      drawAddControls();
      ImGui::EndTable();
    }
  }
  ImGui::End();
}

void StateMachinePanel::drawDiagramCanvas() {
  const auto states = document_->states();
  const auto transitions = document_->transitions();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const glm::vec2 size{std::max(avail.x, 200.0f), std::max(avail.y, 160.0f)};
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const glm::vec2 origin{o.x, o.y};
  ImGui::InvisibleButton("canvas", {size.x, size.y});
  diagram_.layout(states, transitions, size);
  if (ImGui::IsItemClicked()) {
    const glm::vec2 m = glm::vec2(ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y) - origin;
    const auto box = diagram_.boxAt(m);
    const auto arrow = box ? std::nullopt : diagram_.arrowAt(m);
    selectedState_ = box && *box < states.size() ? int(*box) : -1;
    selectedTransition_ = arrow ? int(diagram_.arrows()[*arrow].transition) : -1;
    if (selectedState_ >= 0) std::snprintf(renameInput_, sizeof renameInput_, "%s", states[size_t(selectedState_)].name.c_str());
  }
  tooltipForDiagram(origin);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(o, {o.x + size.x, o.y + size.y}, IM_COL32(24, 27, 36, 255));

  // What the running graph is doing: the active state, the transition in flight.
  const std::string current = currentState();
  std::optional<facial::StateMachineStatus> status;
  if (machine_) status = driver_->graph().stateMachineStatus(*machine_);
  std::string blendingFrom;
  if (status && status->blending && status->liveSource) blendingFrom = states.size() > *status->liveSource ? states[*status->liveSource].name : "";

  for (const DiagramArrow& arrow : diagram_.arrows()) {
    const GraphTransitionInfo& t = transitions[arrow.transition];
    const bool live = status && status->blending && t.to == current && (t.from == blendingFrom || t.from == GraphDocument::kAnyState);
    const bool selected = int(arrow.transition) == selectedTransition_;
    const ImU32 colour = selected ? IM_COL32(255, 190, 90, 255) : live ? IM_COL32(120, 220, 140, 255) : IM_COL32(120, 130, 150, 200);
    const ImVec2 a = screen(origin, arrow.start), b = screen(origin, arrow.end);
    draw->AddLine(a, b, colour, selected || live ? 2.5f : 1.2f);
    drawArrowHead(draw, a, b, colour);
    if (live) draw->AddCircleFilled(screen(origin, arrow.at(status->blendProgress)), 5.0f, IM_COL32(120, 220, 140, 255));
  }
  for (size_t i = 0; i < diagram_.boxes().size(); ++i) {
    const DiagramBox& box = diagram_.boxes()[i];
    const bool active = box.state == current, any = i == states.size();
    const ImU32 fill = active ? IM_COL32(60, 120, 80, 255) : any ? IM_COL32(50, 50, 70, 255) : IM_COL32(44, 52, 70, 255);
    draw->AddRectFilled(screen(origin, box.min), screen(origin, box.max), fill, 4.0f);
    draw->AddRect(screen(origin, box.min), screen(origin, box.max),
                  int(i) == selectedState_ ? IM_COL32(255, 190, 90, 255) : IM_COL32(140, 150, 170, 255), 4.0f, 0,
                  int(i) == selectedState_ ? 2.0f : 1.0f);
    const std::string label = any ? "any state" : box.state;
    const ImVec2 text = ImGui::CalcTextSize(label.c_str());
    const glm::vec2 c = box.centre();
    draw->AddText({origin.x + c.x - text.x * 0.5f, origin.y + c.y - text.y * 0.5f}, IM_COL32(230, 230, 235, 255), label.c_str());
  }
  if (status && status->blending)
    draw->AddText({o.x + 6.0f, o.y + size.y - 18.0f}, IM_COL32(120, 220, 140, 255),
                  ("-> " + current + "  " + std::to_string(int(100.0f * status->blendProgress)) + "%").c_str());
}

// Hovering a box names its state and expression, an arrow its transition; the empty diagram, after a rest, says what a click does.
void StateMachinePanel::tooltipForDiagram(glm::vec2 origin) const {
  const auto states = document_->states();
  const auto transitions = document_->transitions();
  const glm::vec2 m = glm::vec2(ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y) - origin;
  if (const auto box = diagram_.boxAt(m); box && *box < states.size())
    return tooltip("state " + states[*box].name + (states[*box].expression.empty() ? "" : " (" + states[*box].expression + ")") +
                   ": click to rename or remove it");
  if (const auto arrow = diagram_.arrowAt(m)) {
    const GraphTransitionInfo& t = transitions[diagram_.arrows()[*arrow].transition];
    char text[256];
    std::snprintf(text, sizeof text, "%s -> %s%s%s, %.2f s %s: click to edit it", t.from.c_str(), t.to.c_str(),
                  t.trigger.empty() ? "" : " when ", t.trigger.c_str(), double(t.duration), t.easing.c_str());
    return tooltip(text);
  }
  tooltip("States as boxes (the active one green), transitions as arrows (the one blending green, a dot at its progress).\n"
          "Click a box or an arrow to edit it",
          kCanvasHelpDelay);
}

void StateMachinePanel::drawStateEditor() {
  const auto states = document_->states();
  if (selectedState_ < 0 || size_t(selectedState_) >= states.size()) {
    ImGui::TextDisabled("click a state or an arrow");
    return;
  }
  const GraphStateInfo& state = states[size_t(selectedState_)];
  ImGui::Text("state %s", state.name.c_str());
  if (!state.expression.empty()) ImGui::TextDisabled("expression: %s", state.expression.c_str());
  ImGui::SetNextItemWidth(-60.0f);
  ImGui::InputText("##rename", renameInput_, sizeof renameInput_);
  tooltip("The state's new name (then Rename)");
  ImGui::SameLine();
  if (ImGui::Button("Rename")) renameState(state.name, renameInput_);
  tooltip("Rename the state; transitions and the default state follow");
  if (ImGui::Button("Remove state")) removeState(state.name);
  tooltip("Remove the state and every transition into it (Undo brings it back)");
  ImGui::Separator();
}

void StateMachinePanel::drawTransitionEditor() {
  const auto transitions = document_->transitions();
  if (selectedTransition_ < 0 || size_t(selectedTransition_) >= transitions.size()) return;
  // Widgets edit a copy, committed when a drag ends or a box is ticked: one undo step per change.
  if (editingIndex_ != selectedTransition_ || editingRevision_ != document_->revision()) {
    editing_ = transitions[size_t(selectedTransition_)];
    editingExit_ = editing_.exitTime.value_or(1.0f);
    editingHasExit_ = editing_.exitTime.has_value();
    editingIndex_ = selectedTransition_;
    editingRevision_ = document_->revision();
  }
  GraphTransitionInfo& t = editing_;
  ImGui::Text("%s -> %s", t.from.c_str(), t.to.c_str());
  if (!t.trigger.empty()) ImGui::TextDisabled("when: %s", t.trigger.c_str());
  ImGui::DragFloat("duration", &t.duration, 0.01f, 0.01f, 10.0f, "%.2f s");
  bool commit = ImGui::IsItemDeactivatedAfterEdit();
  tooltip("Seconds the blend into the target state takes (drag, or Ctrl+click to type)");
  int easing = 0;
  for (int i = 0; i < 3; ++i)
    if (t.easing == kEasings[i]) easing = i;
  if (ImGui::Combo("easing", &easing, kEasings, 3)) {
    t.easing = kEasings[easing];
    commit = true;
  }
  tooltip("The blend's curve over its duration: linear, cosine (the study's ease), smoothstep");
  commit |= ImGui::Checkbox("exit time", &editingHasExit_);
  tooltip("Seconds the source state must have run before this transition may start");
  if (editingHasExit_) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::DragFloat("##exit", &editingExit_, 0.01f, 0.0f, 30.0f, "%.2f s");
    commit |= ImGui::IsItemDeactivatedAfterEdit();
    tooltip("The exit time in seconds (drag, or Ctrl+click to type)");
  }
  commit |= ImGui::Checkbox("interruptible", &t.interruptible);
  tooltip("May another transition cut in while this one blends");
  if (commit)
    editTransition(t.from, t.to, std::max(t.duration, 0.01f), t.easing,
                   editingHasExit_ ? std::optional<float>(editingExit_) : std::nullopt, t.interruptible);
  if (ImGui::Button("Remove transition")) removeTransition(t.from, t.to);
  tooltip("Remove this arrow (Undo brings it back)");
  ImGui::Separator();
}

void StateMachinePanel::drawAddControls() {
  const auto states = document_->states();
  const auto presets = face_->expressions().names();
  ImGui::TextDisabled("add a state");
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputText("##newstate", newStateInput_, sizeof newStateInput_);
  tooltip("The new state's name");
  newExpression_ = std::clamp(newExpression_, 0, int(presets.size()) - 1);
  ImGui::SetNextItemWidth(-50.0f);
  const bool choosing = ImGui::BeginCombo("##expr", presets.empty() ? "" : std::string(presets[size_t(newExpression_)]).c_str());
  if (!choosing) tooltip("The expression preset the new state holds");
  if (choosing) {
    for (size_t i = 0; i < presets.size(); ++i) {
      if (ImGui::Selectable(std::string(presets[i]).c_str(), int(i) == newExpression_)) newExpression_ = int(i);
      tooltip("The new state holds this preset");
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (ImGui::Button("Add##state") && !presets.empty()) addState(newStateInput_, presets[size_t(newExpression_)]);
  tooltip("Add a state holding the chosen expression preset");
  ImGui::TextDisabled("add a transition");
  const auto stateCombo = [&](const char* id, int& choice, bool withAny, const char* help) {
    const int count = int(states.size()) + (withAny ? 1 : 0);
    choice = std::clamp(choice, 0, count - 1);
    const auto name = [&](int i) { return i < int(states.size()) ? states[size_t(i)].name : std::string(GraphDocument::kAnyState); };
    ImGui::SetNextItemWidth(-1.0f);
    const bool open = ImGui::BeginCombo(id, name(choice).c_str());
    if (!open) tooltip(help);
    if (open) {
      for (int i = 0; i < count; ++i) {
        if (ImGui::Selectable(name(i).c_str(), i == choice)) choice = i;
        tooltip(help);
      }
      ImGui::EndCombo();
    }
    return name(choice);
  };
  const std::string from = stateCombo("##from", newFrom_, true, "The state the new transition leaves (any: from every state)"),
                    to = stateCombo("##to", newTo_, false, "The state the new transition enters");
  ImGui::SetNextItemWidth(-50.0f);
  ImGui::InputTextWithHint("##trigger", "trigger (empty: none)", newTriggerInput_, sizeof newTriggerInput_);
  tooltip("The trigger that fires the new transition (a new name is declared as a parameter; empty: none)");
  ImGui::SameLine();
  if (ImGui::Button("Add##transition")) addTransition(from, to, newTriggerInput_, 0.5f, "cosine");
  tooltip("Add a transition (0.5 s, cosine); a new trigger name is declared as a parameter");
  ImGui::Separator();
  ImGui::BeginDisabled(!document_->canUndo());
  if (ImGui::Button("Undo##graph")) undoGraphEdit();
  tooltip("Undo the last diagram edit");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!document_->canRedo());
  if (ImGui::Button("Redo##graph")) redoGraphEdit();
  tooltip("Redo the diagram edit undone last");
  ImGui::EndDisabled();
  ImGui::SetNextItemWidth(-50.0f);
  ImGui::InputText("##savepath", savePathInput_, sizeof savePathInput_);
  tooltip("Where Save writes the graph (JSON)");
  ImGui::SameLine();
  if (ImGui::Button("Save##graph")) saveGraph(savePathInput_);
  tooltip("Write the graph file the runtime reads (facial play, --graph); save it beside the timeline files it names");
}

}  // namespace editor
