#include "editor/app/control_map_panel.h"
#include "editor/app/tooltip.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/json/json_document.h"

namespace editor {

namespace {

constexpr std::array<ControlMapPanel::Pole, 4> kFourPoles = {{
    {"surprise", {0.0f, 1.0f}}, {"anger", {0.0f, -1.0f}}, {"happy", {1.0f, 0.0f}}, {"sad", {-1.0f, 0.0f}}}};

// Six basic emotions 60 degrees apart, happy on +x, arousal rising toward +y.
std::array<ControlMapPanel::Pole, 6> sixPoles() {
  const char* names[6] = {"happy", "surprise", "fear", "anger", "disgust", "sad"};
  std::array<ControlMapPanel::Pole, 6> poles{};
  for (int i = 0; i < 6; ++i) {
    const float a = float(i) * float(M_PI) / 3.0f;
    poles[size_t(i)] = {names[i], {std::cos(a), std::sin(a)}};
  }
  return poles;
}

facial::Json poseNode(const char* preset) { return {{"type", "pose"}, {"preset", preset}}; }

facial::Json mapGraph(ControlMapPanel::Layout layout) {
  facial::Json root;
  if (layout == ControlMapPanel::Layout::FourPoles) {
    root = {{"type", "controlMap"}, {"neutral", poseNode("neutral")}, {"up", poseNode(kFourPoles[0].emotion)},
            {"down", poseNode(kFourPoles[1].emotion)}, {"right", poseNode(kFourPoles[2].emotion)},
            {"left", poseNode(kFourPoles[3].emotion)}, {"x", "x"}, {"y", "y"}};
  } else {
    facial::Json poles = facial::Json::array();
    for (const auto& pole : sixPoles()) poles.push_back({{"at", {pole.at.x, pole.at.y}}, {"node", poseNode(pole.emotion)}});
    root = {{"type", "freeformMap"}, {"neutral", poseNode("neutral")}, {"poles", poles}, {"x", "x"}, {"y", "y"}};
  }
  return {{"version", 1},
          {"channels", "actionUnits"},
          {"parameters", {{{"name", "x"}, {"type", "float"}}, {{"name", "y"}, {"type", "float"}}}},
          {"root", {{"type", "blink"}, {"input", root}}}};
}

}  // namespace

eng::Result<void> ControlMapPanel::create(const app::FaceSetup& face) {
  const std::vector<std::string> names = face.layout().names();
  for (size_t i = 0; i < drivers_.size(); ++i) {
    const auto layout = Layout(i);
    const char* source = layout == Layout::FourPoles ? "editor control map (4 poles)" : "editor freeform map (6 poles)";
    auto graph = facial::parseGraph(mapGraph(layout), source, {.presets = facial::presetLookup(face.expressions())});
    if (!graph) return graph.error();
    auto driver = facial::FaceDriver::create(*graph, &face.graphRig(), names, face.baseWeights(), 7);
    if (!driver) return driver.error().prefixed(std::string(source) + ": ");
    x_[i] = *(*graph)->findParameter("x");
    y_[i] = *(*graph)->findParameter("y");
    driver->update(0.0f);
    drivers_[i].emplace(std::move(*driver));
  }
  return {};
}

void ControlMapPanel::update(float dt) {
  for (size_t i = 0; i < drivers_.size(); ++i) {
    drivers_[i]->graph().setFloat(x_[i], cursor_.x);
    drivers_[i]->graph().setFloat(y_[i], cursor_.y);
    drivers_[i]->update(dt);
  }
}

void ControlMapPanel::setCursor(glm::vec2 cursor) {
  if (!std::isfinite(cursor.x) || !std::isfinite(cursor.y)) return;
  cursor_ = glm::clamp(cursor, glm::vec2(-1.0f), glm::vec2(1.0f));
}

void ControlMapPanel::dragCursor(glm::vec2 cursor, FaceDelegate& face) {
  setCursor(cursor);
  face.takeControl(FaceSource::ControlMap);
}

void ControlMapPanel::draw(FaceDelegate& face) {
  int layout = int(layout_);
  ImGui::RadioButton("4 poles (study)", &layout, 0);
  tooltip("The study's control map: happy +x, sad -x, surprise +y, anger -y around neutral");
  ImGui::SameLine();
  ImGui::RadioButton("6 poles (freeform)", &layout, 1);
  tooltip("A freeform map of six emotions around neutral");
  layout_ = Layout(layout);

  const float side = std::max(120.0f, std::min(ImGui::GetContentRegionAvail().x, ImGui::GetContentRegionAvail().y - 26.0f));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("pad", {side, side});
  const auto toScreen = [&](glm::vec2 p) {
    return ImVec2(origin.x + (p.x * 0.85f + 1.0f) * 0.5f * side, origin.y + (1.0f - p.y * 0.85f) * 0.5f * side);
  };
  if (ImGui::IsItemActive()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    dragCursor({((m.x - origin.x) / side * 2.0f - 1.0f) / 0.85f, (1.0f - (m.y - origin.y) / side * 2.0f) / 0.85f}, face);
  }
  if (!ImGui::IsItemActive()) tooltip("Drag the cursor: the face blends the poles around it (Record writes it as keys)", kCanvasHelpDelay);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 end{origin.x + side, origin.y + side};
  draw->AddRectFilled(origin, end, IM_COL32(28, 32, 42, 255), 4.0f);
  draw->AddRect(origin, end, IM_COL32(110, 120, 140, 255), 4.0f);
  const ImU32 grid = IM_COL32(70, 80, 100, 255), label = IM_COL32(220, 220, 220, 255);
  if (layout_ == Layout::FourPoles) {
    // The diamond the cursor is pulled back onto.
    draw->AddQuad(toScreen({0, 1}), toScreen({1, 0}), toScreen({0, -1}), toScreen({-1, 0}), grid);
  } else {
    draw->AddCircle(toScreen({0, 0}), side * 0.5f * 0.85f, grid, 48);
  }
  draw->AddLine(toScreen({-1, 0}), toScreen({1, 0}), grid);
  draw->AddLine(toScreen({0, -1}), toScreen({0, 1}), grid);
  draw->AddText({toScreen({0, 0}).x + 3, toScreen({0, 0}).y + 1}, IM_COL32(150, 150, 150, 255), "neutral");
  const auto drawPole = [&](const Pole& pole) {
    const ImVec2 at = toScreen(pole.at);
    draw->AddCircleFilled(at, 4.0f, IM_COL32(120, 190, 255, 255));
    const ImVec2 size = ImGui::CalcTextSize(pole.emotion);
    const float x = std::clamp(at.x - size.x * 0.5f, origin.x + 2.0f, end.x - size.x - 2.0f);
    const float y = pole.at.y < -0.5f ? at.y - size.y - 5.0f : at.y + 5.0f;
    draw->AddText({x, y}, label, pole.emotion);
  };
  if (layout_ == Layout::FourPoles)
    for (const Pole& pole : kFourPoles) drawPole(pole);
  else
    for (const Pole& pole : sixPoles()) drawPole(pole);
  const bool driving = face.source() == FaceSource::ControlMap;
  draw->AddCircleFilled(toScreen(cursor_), 7.0f, driving ? IM_COL32(255, 190, 90, 255) : IM_COL32(150, 150, 150, 255));
  ImGui::Text("x %.2f  y %.2f%s", cursor_.x, cursor_.y, driving ? "  (drives the face)" : "  (drag to drive)");
  message_.draw();
}

}  // namespace editor
