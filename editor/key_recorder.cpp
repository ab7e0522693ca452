#include "editor/key_recorder.h"

#include <algorithm>
#include <cmath>

namespace editor {

namespace {

// Distance in value from sample i to the line through samples a and b.
float valueError(std::span<const float> times, std::span<const float> values, size_t a, size_t b, size_t i) {
  const float span = times[b] - times[a];
  const float t = span > 0.0f ? (times[i] - times[a]) / span : 0.0f;
  return std::abs(values[i] - (values[a] + t * (values[b] - values[a])));
}

}  // namespace

void KeyRecorder::start(std::vector<std::string> channels, float startTime) {
  channels_ = std::move(channels);
  startTime_ = std::isfinite(startTime) ? std::max(startTime, 0.0f) : 0.0f;
  times_.clear();
  values_.clear();
  recording_ = true;
}

void KeyRecorder::sample(float elapsed, std::span<const float> values) {
  if (!recording_ || values.size() != channels_.size() || !std::isfinite(elapsed) || elapsed < 0.0f) return;
  if (!times_.empty() && elapsed <= times_.back() + TimelineDocument::kMinKeySpacing) return;
  for (const float v : values)
    if (!std::isfinite(v)) return;
  times_.push_back(elapsed);
  values_.insert(values_.end(), values.begin(), values.end());
}

std::vector<size_t> KeyRecorder::simplify(std::span<const float> times, std::span<const float> values, float tolerance) {
  if (times.empty()) return {};
  std::vector<size_t> kept{0};
  if (times.size() == 1) return kept;
  std::vector<char> keep(times.size(), 0);
  keep.front() = keep.back() = 1;
  // Iterative Ramer-Douglas-Peucker: split each span at its worst sample until all fit.
  std::vector<std::pair<size_t, size_t>> spans{{0, times.size() - 1}};
  while (!spans.empty()) {
    const auto [a, b] = spans.back();
    spans.pop_back();
    size_t worst = a;
    float worstError = tolerance;
    for (size_t i = a + 1; i < b; ++i)
      if (const float e = valueError(times, values, a, b, i); e > worstError) {
        worst = i;
        worstError = e;
      }
    if (worst == a) continue;
    keep[worst] = 1;
    spans.push_back({a, worst});
    spans.push_back({worst, b});
  }
  kept.clear();
  for (size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) kept.push_back(i);
  return kept;
}

RecordedTrack KeyRecorder::reduce(std::string channel, std::span<const float> values) const {
  const float seconds = times_.empty() ? 0.0f : times_.back() - times_.front();
  const size_t most = std::max<size_t>(2, size_t(std::ceil(options_.maxKeysPerSecond * seconds)) + 1);
  RecordedTrack track{std::move(channel), {}, options_.tolerance};
  std::vector<size_t> kept;
  for (;; track.tolerance *= 2.0f) {
    kept = simplify(times_, values, track.tolerance);
    if (kept.size() <= most || track.tolerance > 1.0f) break;
  }
  for (const size_t i : kept) track.keys.push_back({.time = startTime_ + times_[i], .value = values[i]});
  return track;
}

std::vector<RecordedTrack> KeyRecorder::stop() {
  recording_ = false;
  std::vector<RecordedTrack> tracks;
  const size_t n = channels_.size(), samples = times_.size();
  std::vector<float> values(samples);
  for (size_t c = 0; c < n && samples > 0; ++c) {
    for (size_t s = 0; s < samples; ++s) values[s] = values_[s * n + c];
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    if (*high - *low <= options_.tolerance) continue;  // this channel did not move
    tracks.push_back(reduce(channels_[c], values));
  }
  return tracks;
}

eng::Result<RecordingSummary> writeRecording(TimelineDocument& document, std::span<const RecordedTrack> tracks,
                                             size_t samples) {
  RecordingSummary summary{.samples = samples};
  float first = INFINITY, last = 0.0f;
  for (const RecordedTrack& t : tracks)
    if (!t.keys.empty()) {
      first = std::min(first, t.keys.front().time);
      last = std::max(last, t.keys.back().time);
    }
  if (tracks.empty() || last < first) return summary;
  summary.seconds = last - first;
  // One undo step: Ctrl+Z takes the whole take back.
  ENG_TRY(document.grouped("record", [&]() -> eng::Result<void> {
    if (last > document.duration()) ENG_TRY(document.setDuration(last));
    // The recorded span is replaced: keys already there would bend the gesture.
    document.clearSelection();
    for (const RecordedTrack& t : tracks)
      if (const auto track = document.findTrack(t.channel))
        for (const DocumentKey& k : document.tracks()[*track].keys)
          if (k.key.time >= first - TimelineDocument::kMinKeySpacing && k.key.time <= last + TimelineDocument::kMinKeySpacing)
            document.select(k.id, true);
    if (!document.selection().empty()) ENG_TRY(document.deleteSelected());
    for (const RecordedTrack& t : tracks) {
      const auto found = document.findTrack(t.channel);
      const size_t track = found ? *found : ENG_TRY_VALUE(document.addTrack(t.channel));
      for (const facial::Keyframe& k : t.keys) ENG_TRY(document.setKey(track, k.time, k.value));
      ++summary.tracks;
      summary.keys += t.keys.size();
    }
    return {};
  }));
  return summary;
}

}  // namespace editor
