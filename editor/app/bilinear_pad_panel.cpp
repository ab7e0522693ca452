#include "editor/app/bilinear_pad_panel.h"
#include "editor/app/tooltip.h"

#include <imgui.h>

#include <algorithm>

#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace editor {

namespace {

constexpr const char* kCornerLabels[4] = {"from, row 1", "to, row 1", "from, row 2", "to, row 2"};
size_t actionUnitInputs() { return facial::rigInputCount() - facial::kEmotionCount; }

}  // namespace

eng::Result<std::vector<float>> BilinearPadPanel::presetPose(std::string_view preset) const {
  const facial::ExpressionPreset* found = face_->expressions().find(preset);
  if (!found) return eng::makeError(eng::ErrorKind::NotFound, "bilinear pad: no expression preset '" + std::string(preset) + "'");
  std::vector<float> pose(facial::rigInputCount(), 0.0f);
  const std::span<float> all(pose);
  ENG_TRY(facial::ExpressionLibrary::evaluate(*found, 1.0f, all.first(actionUnitInputs())));
  ENG_TRY(facial::ExpressionLibrary::evaluateEmotions(*found, 1.0f, all.subspan(actionUnitInputs())));
  return pose;
}

eng::Result<void> BilinearPadPanel::create(const app::FaceSetup& face) {
  face_ = &face;
  std::array<std::vector<float>, 4> corners;
  for (size_t i = 0; i < 4; ++i) corners[i] = ENG_TRY_VALUE(presetPose(cornerNames_[i]));
  ENG_TRY(pad_.setCorners(std::move(corners)));
  inputs_.assign(facial::rigInputCount(), 0.0f);
  targets_.assign(face.baseWeights().begin(), face.baseWeights().end());
  if (face.graphRig().expressionStage()) expressionWeights_.assign(face.graphRig().controlNames().size(), 0.0f);
  update();
  return {};
}

void BilinearPadPanel::update() {
  if (!face_ || !pad_.pose(inputs_)) return;
  std::copy(face_->baseWeights().begin(), face_->baseWeights().end(), targets_.begin());
  const std::span<const float> all(inputs_);
  // Sizes fixed at create(), weights blended from presets in [0, 1]: cannot fail.
  (void)face_->graphRig().apply(all.first(actionUnitInputs()), all.subspan(actionUnitInputs()), targets_, expressionWeights_);
}

void BilinearPadPanel::dragTo(float s, float t, FaceDelegate& face) {
  pad_.setPosition(s, t);
  face.takeControl(FaceSource::BilinearPad);
}

bool BilinearPadPanel::chooseCorner(BilinearPad::Corner corner, std::string_view preset) {
  auto pose = presetPose(preset);
  if (!pose) {
    message_.report(pose.error().message, true);
    return false;
  }
  if (auto chosen = pad_.chooseCorner(corner, *pose); !chosen) {
    message_.report(chosen.error().message, true);
    return false;
  }
  cornerNames_[corner] = std::string(preset);
  return true;
}

float BilinearPadPanel::channelValue(std::string_view channel) const {
  const auto input = facial::rigInputIndex(channel);
  return input && *input < inputs_.size() ? inputs_[*input] : 0.0f;
}

void BilinearPadPanel::draw(FaceDelegate& face) {
  // The corner combos laid out as the pad: row 2 over row 1, "from" left, "to" right.
  const auto presets = face_->expressions().names();
  for (const size_t c : {size_t(BilinearPad::Q21), size_t(BilinearPad::Q22), size_t(BilinearPad::Q11), size_t(BilinearPad::Q12)}) {
    ImGui::PushID(int(c));
    if (c % 2 == 1) ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * (c % 2 == 1 ? 1.0f : 0.5f) - 4.0f);
    const bool choosing = ImGui::BeginCombo("##corner", cornerNames_[c].c_str());
    if (!choosing) tooltip(std::string(kCornerLabels[c]) + (c % 2 == 1 ? " (re-bases: the face does not jump)" : ""));
    if (choosing) {
      for (const std::string_view name : presets) {
        if (ImGui::Selectable(std::string(name).c_str(), name == cornerNames_[c])) chooseCorner(BilinearPad::Corner(c), name);
        tooltip("This expression preset at the corner");
      }
      ImGui::EndCombo();
    }
    ImGui::PopID();
  }
  const float side = std::max(100.0f, std::min(ImGui::GetContentRegionAvail().x, ImGui::GetContentRegionAvail().y - 26.0f));
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("bilinear", {side, side});
  if (ImGui::IsItemActive()) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    dragTo(1.0f - (m.y - o.y) / side, (m.x - o.x) / side, face);
  }
  if (!ImGui::IsItemActive()) tooltip("Drag: t across from the \"from\" column to the \"to\" column, s up from row 1 to row 2", kCanvasHelpDelay);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(o, {o.x + side, o.y + side}, IM_COL32(28, 32, 42, 255), 4.0f);
  draw->AddRect(o, {o.x + side, o.y + side}, IM_COL32(110, 120, 140, 255), 4.0f);
  const ImU32 label = IM_COL32(200, 200, 210, 255);
  // Corners: Q11 bottom left, Q12 bottom right, Q21 top left, Q22 top right.
  const ImVec2 at[4] = {{o.x + 4, o.y + side - 18}, {o.x + side - 4, o.y + side - 18}, {o.x + 4, o.y + 4}, {o.x + side - 4, o.y + 4}};
  for (size_t c = 0; c < 4; ++c) {
    const float w = ImGui::CalcTextSize(cornerNames_[c].c_str()).x;
    draw->AddText({c % 2 == 1 ? at[c].x - w : at[c].x, at[c].y}, label, cornerNames_[c].c_str());
  }
  const bool driving = face.source() == FaceSource::BilinearPad;
  const ImVec2 cursor{o.x + pad_.t() * side, o.y + (1.0f - pad_.s()) * side};
  draw->AddCircleFilled(cursor, 7.0f, driving ? IM_COL32(255, 190, 90, 255) : IM_COL32(150, 150, 150, 255));
  ImGui::Text("s %.2f  t %.2f%s", pad_.s(), pad_.t(), driving ? "  (drives the face)" : "  (drag to drive)");
  message_.draw();
}

}  // namespace editor
