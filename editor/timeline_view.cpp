#include "editor/timeline_view.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>

#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/rig/rig_mapping.h"

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
  std::vector<TrackRow> rows(tracks.size());
  for (size_t t = 0; t < tracks.size(); ++t) rows[t].track = t;
  return hitAt(tracks, rows, pixel);
}

std::optional<TimelineView::Hit> TimelineView::hitAt(std::span<const DocumentTrack> tracks, std::span<const TrackRow> rows,
                                                     glm::vec2 pixel) const {
  const auto row = rowAt(pixel.y);
  if (!row || *row >= rows.size()) return std::nullopt;
  Hit hit{.row = *row};
  if (!rows[*row].track || *rows[*row].track >= tracks.size()) return hit;
  float best = kKeyHitRadius;
  for (const DocumentKey& k : tracks[*rows[*row].track].keys) {
    const float d = std::hypot(xAt(k.key.time) - pixel.x, yAt(*row, k.key.value) - pixel.y);
    if (d < best) {
      best = d;
      hit.key = k.id;
    }
  }
  return hit;
}

float TimelineView::rulerLabelStep(float duration) { return duration <= 3.0f ? 0.5f : duration <= 12.0f ? 1.0f : 5.0f; }

void TimelineView::showTime(const TimeWindow& window) {
  if (!(window.span() > 0.0f)) return;
  timeStart_ = window.start;
  pixelsPerSecond_ = canvasWidth_ / window.span();
}

void TimeWindow::zoom(float anchor, float factor) {
  if (!std::isfinite(anchor) || !(factor > 0.0f)) return;
  const float newSpan = std::max(span() / factor, kMinSpan);
  const float share = span() > 0.0f ? (anchor - start) / span() : 0.5f;
  start = anchor - share * newSpan;
  end = start + newSpan;
}

void TimeWindow::pan(float seconds) {
  if (!std::isfinite(seconds)) return;
  start += seconds;
  end += seconds;
}

void TimeWindow::frame(float t0, float t1) {
  if (!std::isfinite(t0) || !std::isfinite(t1)) return;
  if (t0 > t1) std::swap(t0, t1);
  const float margin = std::max(0.05f * (t1 - t0), 0.5f * std::max(kMinSpan - (t1 - t0), 0.0f));
  start = t0 - margin;
  end = t1 + margin;
}

void TimeWindow::clampTo(float duration) {
  const float s = std::clamp(span(), kMinSpan, std::max(2.0f * duration, kMinSpan));
  start = std::clamp(start, -0.5f * s, std::max(duration - 0.5f * s, -0.5f * s));
  end = start + s;
}

namespace {

bool containsWord(const std::string& lower, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (lower.find(w) != std::string::npos) return true;
  return false;
}

}  // namespace

std::string_view trackGroupName(TrackGroup group) {
  static constexpr std::array<std::string_view, kTrackGroupCount> kNames = {"brows", "eyes",     "cheeks",  "mouth",
                                                                            "jaw",   "emotions", "visemes", "targets"};
  return kNames[size_t(group)];
}

TrackGroup trackGroupOf(std::string_view channel) {
  std::string lower(channel);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (std::string_view e : facial::emotionNames())
    if (lower == e) return TrackGroup::Emotions;
  if (facial::rigVisemeIndex(channel)) return TrackGroup::Visemes;
  if (containsWord(lower, {"brow"})) return TrackGroup::Brows;
  if (containsWord(lower, {"eye", "lid", "blink", "squint"})) return TrackGroup::Eyes;
  if (containsWord(lower, {"cheek", "nose", "sneer"})) return TrackGroup::Cheeks;
  if (containsWord(lower, {"jaw"})) return TrackGroup::Jaw;
  if (containsWord(lower, {"mouth", "lip", "chin", "tongue", "smile", "frown", "pucker", "funnel", "dimple"}))
    return TrackGroup::Mouth;
  return TrackGroup::Targets;
}

std::vector<TrackRow> layoutTrackRows(std::span<const DocumentTrack> tracks, std::span<const bool> collapsed) {
  std::vector<TrackRow> rows;
  for (size_t g = 0; g < kTrackGroupCount; ++g) {
    const auto group = TrackGroup(g);
    bool header = false;
    for (size_t t = 0; t < tracks.size(); ++t) {
      if (trackGroupOf(tracks[t].channel) != group) continue;
      if (!header) rows.push_back({group, std::nullopt});
      header = true;
      if (g >= collapsed.size() || !collapsed[g]) rows.push_back({group, t});
    }
  }
  return rows;
}

}  // namespace editor
