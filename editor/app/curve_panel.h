#pragma once
// The curve view (a tab of the timeline panel): the shown tracks' weight over
// time overlaid in colour (editor/curve_model.h draws and hit-tests), tangent
// handles on the selected keys (drag: smooth; Alt+drag: broken), a box drag
// on empty space selects, the selected key's mode and numbers edited in
// fields. Every edit goes through the TimelineDocument (undoable).
#include <optional>
#include <span>

#include "editor/curve_model.h"
#include "editor/timeline_document.h"
#include "editor/timeline_view.h"

namespace editor {

class CurvePanel {
 public:
  // tracks: the tracks to overlay; window: the time axis shared with the dope sheet.
  void draw(TimelineDocument& document, std::span<const size_t> tracks, const TimeWindow& window, float playhead);

 private:
  void drawKeyFields(TimelineDocument& document);
  void handleMouse(TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view);
  // Hovering a key says its track, time, value and mode; a handle, its slope; the empty plot, after a rest, how to use it.
  void tooltipForPlot(const TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view) const;
  void drawCurves(const TimelineDocument& document, std::span<const size_t> tracks, const CurveView& view,
                  float playhead) const;

  std::optional<CurveView::Hit> dragging_;  // the key or handle being dragged
  glm::vec2 dragStart_{0.0f};
  std::optional<glm::vec2> boxStart_;       // a box selection being drawn
};

}  // namespace editor
