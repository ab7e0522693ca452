#pragma once
// The timeline panel's key canvas as geometry, without ImGui: where a time,
// a value and a track row land in window pixels, the way back (scrubbing and
// dragging keys), which key a click hits, and the ruler's tick spacing. The
// panel (editor/app/timeline_panel.cpp) fits one view per frame to the space
// it has and draws and hit-tests through it.
//
//   const TimelineView view = TimelineView::fit({.left = x, .top = y, .width = w, .height = h}, doc);
//   if (auto key = view.keyAt(doc.tracks(), mouse)) ...
//   seek(view.timeAt(mouse.x));
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "editor/timeline_document.h"

namespace editor {

// The space the canvas is given (window pixels, y down): the track names on
// the left, the ruler along the top, one row per track below it.
struct TimelineArea {
  float left = 0.0f, top = 0.0f;
  float width = 0.0f, height = 0.0f;
  float nameColumn = 170.0f;   // the track names' width, left of the keys
  float rulerHeight = 20.0f;   // the time ruler, above the rows
};

// The dope sheet's groups, in the order they are shown: a track joins the
// first whose words its channel name holds (rig inputs and model targets alike).
enum class TrackGroup : uint8_t { Brows, Eyes, Cheeks, Mouth, Jaw, Emotions, Visemes, Targets };
inline constexpr size_t kTrackGroupCount = 8;
std::string_view trackGroupName(TrackGroup group);
TrackGroup trackGroupOf(std::string_view channel);

// One row of the dope sheet: a group's header, or a track under it.
struct TrackRow {
  TrackGroup group = TrackGroup::Targets;
  std::optional<size_t> track;  // none: the group's header row
};
// Rows for `tracks`: each group that has tracks gets a header, then its
// tracks in document order unless the group is collapsed (collapsed[group]).
std::vector<TrackRow> layoutTrackRows(std::span<const DocumentTrack> tracks, std::span<const bool> collapsed);

// The part of the time axis the canvas shows: zoomed with the wheel, panned
// with a drag, framed on the selection or the whole clip.
struct TimeWindow {
  static constexpr float kMinSpan = 0.05f;  // seconds across the canvas at most zoom
  float start = 0.0f, end = 2.0f;
  float span() const { return end - start; }
  // Zoom by `factor` (> 1: closer) keeping `anchor` (a time) where it is.
  void zoom(float anchor, float factor);
  void pan(float seconds);
  // Shows [t0, t1] with a 5 % margin each side (at least kMinSpan).
  void frame(float t0, float t1);
  // Keeps the window inside [-span/2, duration + span/2] and at most 2x the clip long.
  void clampTo(float duration);
};

class TimelineView {
 public:
  static constexpr float kMinRowHeight = 22.0f, kMaxRowHeight = 44.0f;
  static constexpr float kRowMargin = 3.0f;     // a key's value range stays this far inside its row
  static constexpr float kKeyHitRadius = 7.0f;  // a click this close (pixels) to a key takes it

  // Rows share the height left under the ruler (22 to 44 px each); the keys
  // use the width right of the names (at least 50 px), the clip's duration
  // across it, the document's value range up each row.
  static TimelineView fit(const TimelineArea& area, size_t trackCount, float duration, float minValue, float maxValue);
  static TimelineView fit(const TimelineArea& area, const TimelineDocument& document) {
    return fit(area, document.tracks().size(), document.duration(), document.minValue(), document.maxValue());
  }

  float canvasLeft() const { return canvasLeft_; }
  float canvasRight() const { return canvasLeft_ + canvasWidth_; }
  float canvasWidth() const { return canvasWidth_; }
  float top() const { return top_; }          // the ruler's top
  float rowsTop() const { return rowsTop_; }  // the ruler's bottom, the first row's top
  float rowHeight() const { return rowHeight_; }
  float rowTop(size_t row) const { return rowsTop_ + float(row) * rowHeight_; }
  float rowsBottom() const { return rowTop(trackCount_); }
  // The canvas's height: ruler and rows, at least one row even without tracks.
  float canvasHeight() const;

  // Shows `window` across the canvas instead of the whole clip (zoom and pan).
  void showTime(const TimeWindow& window);
  float timeStart() const { return timeStart_; }
  float timeEnd() const { return timeStart_ + canvasWidth_ / pixelsPerSecond_; }
  float xAt(float time) const { return canvasLeft_ + (time - timeStart_) * pixelsPerSecond_; }
  float timeAt(float x) const { return timeStart_ + (x - canvasLeft_) / pixelsPerSecond_; }
  float yAt(size_t row, float value) const;
  // A drag of (dx, dy) pixels as seconds and value (up is more).
  float secondsFor(float dx) const { return dx / pixelsPerSecond_; }
  float valueFor(float dy) const { return -dy * valuePerPixel_; }

  // The track row under window height y; none on the ruler or below the last row.
  std::optional<size_t> rowAt(float y) const;
  // The key nearest `pixel` in the row under it, within kKeyHitRadius; none elsewhere.
  struct Hit {
    size_t row = 0;
    std::optional<KeyId> key;
  };
  std::optional<Hit> hitAt(std::span<const DocumentTrack> tracks, glm::vec2 pixel) const;
  // The same over grouped rows (layoutTrackRows); Hit::row is the row, a header row has no key.
  std::optional<Hit> hitAt(std::span<const DocumentTrack> tracks, std::span<const TrackRow> rows, glm::vec2 pixel) const;

  // The ruler: a label every labelStep seconds (0.5 s on clips up to 3 s, 1 s
  // up to 12 s, else 5 s) and five ticks per label.
  static float rulerLabelStep(float duration);

 private:
  size_t trackCount_ = 0;
  float canvasLeft_ = 0.0f, canvasWidth_ = 0.0f;
  float top_ = 0.0f, rowsTop_ = 0.0f, rowHeight_ = kMinRowHeight;
  float pixelsPerSecond_ = 1.0f;
  float timeStart_ = 0.0f;
  float minValue_ = 0.0f, valueSpan_ = 1.0f, valuePerPixel_ = 1.0f;
};

}  // namespace editor
