#include "editor/timeline_view.h"

#include <algorithm>
#include <cmath>

namespace editor {

TimelineView TimelineView::fit(const TimelineArea& area, size_t trackCount, float duration, float minValue,
                               float maxValue) {
  TimelineView view;
  view.trackCount_ = trackCount;
  view.rowHeight_ = std::clamp((area.height - area.rulerHeight) / float(std::max<size_t>(trackCount, 1)), kMinRowHeight,
                               kMaxRowHeight);
  view.canvasLeft_ = area.left + area.nameColumn;
  // 8 px of air right of the clip's end.
  view.canvasWidth_ = std::max(area.width - area.nameColumn - 8.0f, 50.0f);
  view.pixelsPerSecond_ = view.canvasWidth_ / duration;
  view.top_ = area.top;
  view.rowsTop_ = area.top + area.rulerHeight;
  view.minValue_ = minValue;
  view.valueSpan_ = maxValue - minValue;
  view.valuePerPixel_ = view.valueSpan_ / std::max(view.rowHeight_ - 2.0f * kRowMargin, 1.0f);
  return view;
}

float TimelineView::canvasHeight() const {
  return (rowsTop_ - top_) + rowHeight_ * float(std::max<size_t>(trackCount_, 1));
}

float TimelineView::yAt(size_t row, float value) const {
  const float top = rowTop(row) + kRowMargin, bottom = rowTop(row + 1) - kRowMargin;
  return bottom - (value - minValue_) / valueSpan_ * (bottom - top);
}

std::optional<size_t> TimelineView::rowAt(float y) const {
  if (!(y >= rowsTop_)) return std::nullopt;
  const float row = std::floor((y - rowsTop_) / rowHeight_);
  if (row >= float(trackCount_)) return std::nullopt;
  return size_t(row);
}

std::optional<TimelineView::Hit> TimelineView::hitAt(std::span<const DocumentTrack> tracks, glm::vec2 pixel) const {
  const auto row = rowAt(pixel.y);
  if (!row || *row >= tracks.size()) return std::nullopt;
  Hit hit{.row = *row};
  float best = kKeyHitRadius;
  for (const DocumentKey& k : tracks[*row].keys) {
    const float d = std::hypot(xAt(k.key.time) - pixel.x, yAt(*row, k.key.value) - pixel.y);
    if (d < best) {
      best = d;
      hit.key = k.id;
    }
  }
  return hit;
}

float TimelineView::rulerLabelStep(float duration) { return duration <= 3.0f ? 0.5f : duration <= 12.0f ? 1.0f : 5.0f; }

}  // namespace editor
