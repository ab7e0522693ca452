#include "editor/app/curve_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>

#include "editor/app/tooltip.h"

namespace editor {

void CurvePanel::draw(TimelineDocument& document, std::span<const size_t> tracks, const TimeWindow& window, float playhead) {
  drawKeyFields(document);
  const ImVec2 origin = ImGui::GetCursorScreenPos(), avail = ImGui::GetContentRegionAvail();
  const CurveView view = CurveView::fit({.left = origin.x, .top = origin.y, .width = avail.x, .height = avail.y}, window,
                                        document.minValue(), document.maxValue());
  ImGui::InvisibleButton("curves", {std::max(avail.x, 50.0f), std::max(avail.y, 2.0f * CurveView::kValueMargin + 20.0f)});
  handleMouse(document, tracks, view);
  tooltipForPlot(document, tracks, view);
  drawCurves(document, tracks, view, playhead);
}

// The first selected key: its mode, time, value and slopes as fields (the numeric edit).
void CurvePanel::drawKeyFields(TimelineDocument& document) {
  const DocumentKey* key = document.selection().empty() ? nullptr : document.key(document.selection().front());
  if (!key) {
    ImGui::TextDisabled("Select a key (click, or drag a box) to edit its tangents; Alt+drag a handle breaks it.");
    return;
  }
  const KeyId id = key->id;
  facial::Keyframe k = key->key;
  int mode = int(curveKeyModeOf(k));
  static constexpr const char* kModes[] = {"auto", "smooth", "flat", "broken", "linear", "step", "cosine"};
  ImGui::SetNextItemWidth(90.0f);
  if (ImGui::Combo("mode", &mode, kModes, int(std::size(kModes))))
    (void)setCurveKeyMode(document, id, CurveKeyMode(mode), k.inTangent, k.outTangent);
  tooltip("The key's tangents / the segment it starts (also for the runtime): auto, smooth, flat, broken, linear, step, cosine");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80.0f);
  float values[2] = {k.time, k.value};
  if (ImGui::InputFloat2("time, value", values, "%.3f", ImGuiInputTextFlags_EnterReturnsTrue))
    (void)document.moveSelectedBy(values[0] - k.time, values[1] - k.value);
  tooltip("The key's time (seconds) and value; Enter moves the selected keys by the change");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(140.0f);
  float slopes[2] = {k.inTangent, k.outTangent};
  if (ImGui::InputFloat2("in, out slope", slopes, "%.3f", ImGuiInputTextFlags_EnterReturnsTrue))
    (void)setCurveKeyMode(document, id, k.tangent == facial::TangentMode::Broken ? CurveKeyMode::Broken : CurveKeyMode::Smooth,
                          slopes[0], slopes[1] != k.outTangent ? slopes[1] : slopes[0]);
  tooltip("Value per second; a smooth key keeps one slope both sides, Enter sets them");
  ImGui::SameLine();
  ImGui::TextDisabled("%zu selected", document.selection().size());
}

void CurvePanel::tooltipForPlot(const TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view) const {
  if (dragging_ || boxStart_) return;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (const auto hit = view.hitAt(document, tracks, {mouse.x, mouse.y}))
    if (const DocumentKey* k = document.key(hit->key)) {
      const std::string key = keyHoverText(document.tracks()[hit->track].channel, k->key, document.frameRate());
      if (hit->part == CurveView::Part::Key) return tooltip(key);
      char slope[96];
      std::snprintf(slope, sizeof slope, "\n%s slope %.3f per second (drag: smooth, Alt+drag: broken)",
                    hit->part == CurveView::Part::InHandle ? "in" : "out",
                    double(hit->part == CurveView::Part::InHandle ? k->key.inTangent : k->key.outTangent));
      return tooltip(key + slope);
    }
  tooltip("Click a key: select (Shift / Ctrl: toggle), drag: move; drag a handle: bend the tangent (Alt: break it).\n"
          "Drag on empty space: box select in time and value",
          kCanvasHelpDelay);
}

// A press on a handle or key drags it (Alt: breaks the tangent); on empty
// space it starts a box (Shift: extend, Ctrl: toggle).
void CurvePanel::handleMouse(TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 mouse{io.MousePos.x, io.MousePos.y};
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    dragging_ = view.hitAt(document, tracks, mouse);
    dragStart_ = mouse;
    if (dragging_ && dragging_->part == CurveView::Part::Key) {
      if (io.KeyCtrl || io.KeyShift) document.selectKeys(std::span(&dragging_->key, 1), SelectMode::Toggle);
      else if (!document.isSelected(dragging_->key)) document.select(dragging_->key);
    }
    if (dragging_) document.beginMove();
    else boxStart_ = mouse;
  }
  if (ImGui::IsItemActive() && dragging_) {
    const DocumentKey* key = document.key(dragging_->key);
    if (key && dragging_->part == CurveView::Part::Key) {
      document.moveSelected(view.timeAt(mouse.x) - view.timeAt(dragStart_.x), view.valueAt(mouse.y) - view.valueAt(dragStart_.y));
    } else if (key) {
      const bool in = dragging_->part == CurveView::Part::InHandle;
      const float slope = view.slopeToward(key->key, mouse, in);
      // The dragged side takes the slope; the other side follows unless the tangent is (or is being) broken.
      const bool broken = io.KeyAlt || key->key.tangent == facial::TangentMode::Broken;
      const float inSlope = in ? slope : key->key.inTangent;
      const float outSlope = in ? (broken ? key->key.outTangent : slope) : slope;
      document.dragTangent(key->id, inSlope, outSlope, io.KeyAlt);
    }
  } else if (!ImGui::IsItemActive()) {
    if (dragging_) document.endMove();
    dragging_.reset();
    if (boxStart_) {
      const SelectMode mode = io.KeyCtrl ? SelectMode::Toggle : io.KeyShift ? SelectMode::Extend : SelectMode::Replace;
      document.selectKeys(document.keysInBox(view.timeAt(boxStart_->x), view.timeAt(mouse.x), tracks,
                                             view.valueAt(boxStart_->y), view.valueAt(mouse.y)),
                          mode);
      boxStart_.reset();
    }
  }
}

void CurvePanel::drawCurves(const TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view,
                            float playhead) const {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect({view.left(), view.top()}, {view.right(), view.bottom()}, true);
  draw->AddRectFilled({view.left(), view.top()}, {view.right(), view.bottom()}, IM_COL32(30, 33, 40, 255));
  for (float v : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f})
    draw->AddLine({view.left(), view.yAt(v)}, {view.right(), view.yAt(v)}, IM_COL32(55, 60, 72, 255));
  for (size_t n = 0; n < tracks.size(); ++n) {
    if (tracks[n] >= document.tracks().size()) continue;
    const DocumentTrack& track = document.tracks()[tracks[n]];
    const ImU32 colour = curveColour(n);
    std::vector<ImVec2> line;
    for (const glm::vec2 s : view.curveSamples(track.keys)) line.push_back({view.xAt(s.x), view.yAt(s.y)});
    draw->AddPolyline(line.data(), int(line.size()), colour, 0, 2.0f);
    draw->AddText({view.left() + 6.0f, view.top() + 4.0f + 16.0f * float(n)}, colour, track.channel.c_str());
    for (size_t i = 0; i < track.keys.size(); ++i) {
      const DocumentKey& k = track.keys[i];
      const glm::vec2 at = view.pixelOf(k.key);
      const bool selected = document.isSelected(k.id);
      if (selected && CurveView::hasInHandle(track.keys, i)) {
        const glm::vec2 h = view.inHandle(k.key);
        draw->AddLine({at.x, at.y}, {h.x, h.y}, IM_COL32(200, 200, 210, 255));
        draw->AddCircleFilled({h.x, h.y}, 4.0f, IM_COL32(200, 200, 210, 255));
      }
      if (selected && CurveView::hasOutHandle(track.keys, i)) {
        const glm::vec2 h = view.outHandle(k.key);
        draw->AddLine({at.x, at.y}, {h.x, h.y}, IM_COL32(200, 200, 210, 255));
        draw->AddCircleFilled({h.x, h.y}, 4.0f, IM_COL32(200, 200, 210, 255));
      }
      draw->AddCircleFilled({at.x, at.y}, 5.0f, selected ? IM_COL32(255, 180, 60, 255) : IM_COL32(235, 235, 240, 255), 12);
    }
  }
  const float px = view.xAt(playhead);
  draw->AddLine({px, view.top()}, {px, view.bottom()}, IM_COL32(255, 80, 80, 255), 2.0f);
  if (boxStart_) {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    draw->AddRectFilled({boxStart_->x, boxStart_->y}, mouse, IM_COL32(120, 160, 255, 40));
    draw->AddRect({boxStart_->x, boxStart_->y}, mouse, IM_COL32(120, 160, 255, 200));
  }
  if (tracks.empty())
    draw->AddText({view.left() + 10.0f, view.top() + 10.0f}, IM_COL32(160, 160, 170, 255),
                  "No curves: select keys or a track in the dope sheet.");
  draw->PopClipRect();
}

}  // namespace editor
