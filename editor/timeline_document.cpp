#include "editor/timeline_document.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "editor/atomic_file.h"
#include "facial/runtime/graph/timeline_json.h"

namespace editor {

namespace {

std::string seconds(float t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", double(t));
  return text;
}

// Catmull-Rom slope through the neighbours (flat at the ends).
float autoSlope(const std::vector<DocumentKey>& keys, size_t i) {
  if (i == 0 || i + 1 >= keys.size()) return 0.0f;
  const facial::Keyframe& a = keys[i - 1].key;
  const facial::Keyframe& b = keys[i + 1].key;
  return (b.value - a.value) / (b.time - a.time);
}

}  // namespace

TimelineDocument::TimelineDocument(std::string name, float duration) {
  state_.name = std::move(name);
  state_.duration = std::isfinite(duration) ? std::max(duration, kMinDuration) : 2.0f;
  state_.serial = nextSerial_++;
  savedSerial_ = state_.serial;
}

eng::Result<TimelineDocument> TimelineDocument::fromTimeline(const facial::Timeline& timeline) {
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed("timeline '" + timeline.name + "': ");
  TimelineDocument doc(timeline.name, timeline.duration);
  doc.state_.loop = timeline.loop;
  for (size_t t = 0; t < timeline.tracks.size(); ++t) {
    DocumentTrack track{timeline.tracks[t].channel, {}};
    for (const facial::Keyframe& k : timeline.trackKeys(t)) track.keys.push_back({doc.nextId_++, k, false});
    doc.state_.tracks.push_back(std::move(track));
  }
  return doc;
}

eng::Result<TimelineDocument> TimelineDocument::load(const std::filesystem::path& path) {
  auto timeline = facial::loadTimeline(path);
  if (!timeline) return timeline.error();
  auto doc = fromTimeline(*timeline);
  if (!doc) return doc.error().prefixed(path.string() + ": ");
  return doc;
}

facial::Timeline TimelineDocument::toTimeline() const {
  facial::Timeline timeline;
  timeline.name = state_.name;
  timeline.duration = state_.duration;
  timeline.loop = state_.loop;
  std::vector<facial::Keyframe> keys;
  for (const DocumentTrack& track : state_.tracks) {
    if (track.keys.empty()) continue;
    keys.clear();
    for (const DocumentKey& k : track.keys) keys.push_back(k.key);
    timeline.addTrack(track.channel, keys);
  }
  return timeline;
}

eng::Result<void> TimelineDocument::save(const std::filesystem::path& path) {
  for (const DocumentTrack& track : state_.tracks)
    if (track.keys.empty())
      return eng::makeError(eng::ErrorKind::Malformed, path.string() + ": not saved: track '" + track.channel +
                            "' has no keys (add a key or remove the track)");
  const facial::Timeline timeline = toTimeline();
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed(path.string() + ": not saved: ");
  auto saved = replaceFileAtomically(path, [&](const std::filesystem::path& temp) -> eng::Result<void> {
    std::ofstream out(temp, std::ios::binary);
    if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot write (" + temp.string() + " cannot be created)");
    out << facial::timelineToJson(timeline).dump(1) << '\n';
    out.close();
    if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": write failed (disk full?)");
    return {};
  });
  if (!saved) return saved;
  savedSerial_ = state_.serial;
  return {};
}

std::optional<size_t> TimelineDocument::findTrack(std::string_view channel) const {
  for (size_t t = 0; t < state_.tracks.size(); ++t)
    if (state_.tracks[t].channel == channel) return t;
  return std::nullopt;
}

std::optional<KeyLocation> TimelineDocument::locate(KeyId id) const {
  for (size_t t = 0; t < state_.tracks.size(); ++t) {
    const auto& keys = state_.tracks[t].keys;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i].id == id) return KeyLocation{t, i};
  }
  return std::nullopt;
}

const DocumentKey* TimelineDocument::key(KeyId id) const {
  const auto where = locate(id);
  return where ? &state_.tracks[where->track].keys[where->index] : nullptr;
}

float TimelineDocument::sample(size_t track, float time) const {
  if (track >= state_.tracks.size()) return 0.0f;
  const auto& keys = state_.tracks[track].keys;
  if (keys.empty()) return 0.0f;
  if (keys.size() == 1 || time <= keys.front().key.time) return keys.front().key.value;
  if (time >= keys.back().key.time) return keys.back().key.value;
  // Binary search over the document's own array (no copy into Keyframe spans).
  const auto after = std::upper_bound(keys.begin(), keys.end(), time,
                                      [](float t, const DocumentKey& k) { return t < k.key.time; });
  const DocumentKey& k1 = *after;
  const DocumentKey& k0 = *(after - 1);
  return facial::interpolateSegment(k0.key, k1.key, time);
}

void TimelineDocument::setValueRange(float minValue, float maxValue) {
  if (!(std::isfinite(minValue) && std::isfinite(maxValue) && minValue < maxValue)) return;
  minValue_ = minValue;
  maxValue_ = maxValue;
}

bool TimelineDocument::isSelected(KeyId id) const {
  return std::find(selection_.begin(), selection_.end(), id) != selection_.end();
}

void TimelineDocument::select(KeyId id, bool additive) {
  if (!locate(id)) return;
  if (!additive) {
    selection_.assign(1, id);
    return;
  }
  if (auto it = std::find(selection_.begin(), selection_.end(), id); it != selection_.end())
    selection_.erase(it);
  else
    selection_.push_back(id);
}

void TimelineDocument::selectTrack(size_t track) {
  selection_.clear();
  if (track >= state_.tracks.size()) return;
  for (const DocumentKey& k : state_.tracks[track].keys) selection_.push_back(k.id);
}

void TimelineDocument::dropStaleSelection() {
  std::erase_if(selection_, [&](KeyId id) { return !locate(id); });
}

void TimelineDocument::normaliseTrack(DocumentTrack& track) const {
  auto& keys = track.keys;
  for (DocumentKey& k : keys) {
    k.key.time = std::clamp(k.key.time, 0.0f, state_.duration);
    k.key.value = std::clamp(k.key.value, minValue_, maxValue_);
  }
  std::stable_sort(keys.begin(), keys.end(),
                   [](const DocumentKey& a, const DocumentKey& b) { return a.key.time < b.key.time; });
  // Keys closer than the minimum spacing are one key: a selected (moved) key
  // wins over an unselected one, otherwise the later one in edit order.
  std::vector<DocumentKey> kept;
  kept.reserve(keys.size());
  for (DocumentKey& k : keys) {
    if (!kept.empty() && k.key.time - kept.back().key.time < kMinKeySpacing) {
      if (isSelected(kept.back().id) && !isSelected(k.id)) continue;
      kept.back() = k;
      continue;
    }
    kept.push_back(k);
  }
  keys = std::move(kept);
  for (size_t i = 0; i < keys.size(); ++i) {
    if (!keys[i].autoTangents || keys[i].key.interpolation != facial::KeyInterpolation::Hermite) continue;
    keys[i].key.outTangent = autoSlope(keys, i);
    if (i + 1 < keys.size()) keys[i + 1].key.inTangent = autoSlope(keys, i + 1);
  }
}

void TimelineDocument::commit(std::string label, State before) {
  state_.serial = nextSerial_++;
  undo_.push_back({std::move(label), std::move(before)});
  redo_.clear();
  ++revision_;
  dropStaleSelection();
}

eng::Result<size_t> TimelineDocument::addTrack(std::string channel) {
  if (channel.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "a track needs a channel name");
  if (findTrack(channel)) return eng::makeError(eng::ErrorKind::InvalidArgument, "there is already a track for '" + channel + "'");
  State before = state_;
  state_.tracks.push_back({std::move(channel), {}});
  commit("add track", std::move(before));
  return state_.tracks.size() - 1;
}

eng::Result<void> TimelineDocument::removeTrack(size_t track) {
  if (track >= state_.tracks.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "no track " + std::to_string(track) + " (" + std::to_string(state_.tracks.size()) + " tracks)");
  State before = state_;
  state_.tracks.erase(state_.tracks.begin() + std::ptrdiff_t(track));
  commit("remove track", std::move(before));
  return {};
}

eng::Result<KeyId> TimelineDocument::setKey(size_t track, float time, float value, facial::KeyInterpolation interpolation) {
  if (track >= state_.tracks.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "no track " + std::to_string(track) + " (" + std::to_string(state_.tracks.size()) + " tracks)");
  if (!std::isfinite(time) || !std::isfinite(value)) return eng::makeError(eng::ErrorKind::InvalidArgument, "key time and value must be finite numbers");
  State before = state_;
  time = std::clamp(time, 0.0f, state_.duration);
  auto& keys = state_.tracks[track].keys;
  KeyId id = 0;
  for (DocumentKey& k : keys) {
    if (std::abs(k.key.time - time) < kMinKeySpacing) {
      k.key.value = value;
      k.key.interpolation = interpolation;
      k.autoTangents = interpolation == facial::KeyInterpolation::Hermite;
      id = k.id;
      break;
    }
  }
  if (id == 0) {
    id = nextId_++;
    facial::Keyframe k;
    k.time = time;
    k.value = value;
    k.interpolation = interpolation;
    keys.push_back({id, k, interpolation == facial::KeyInterpolation::Hermite});
  }
  selection_.assign(1, id);
  normaliseTrack(state_.tracks[track]);
  commit("set key", std::move(before));
  return id;
}

eng::Result<void> TimelineDocument::deleteSelected() {
  if (selection_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no keys selected");
  State before = state_;
  for (DocumentTrack& track : state_.tracks) {
    std::erase_if(track.keys, [&](const DocumentKey& k) { return isSelected(k.id); });
    normaliseTrack(track);
  }
  selection_.clear();
  commit("delete keys", std::move(before));
  return {};
}

eng::Result<void> TimelineDocument::setSelectedInterpolation(facial::KeyInterpolation interpolation) {
  if (selection_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no keys selected");
  State before = state_;
  for (DocumentTrack& track : state_.tracks) {
    for (DocumentKey& k : track.keys) {
      if (!isSelected(k.id)) continue;
      k.key.interpolation = interpolation;
      k.autoTangents = interpolation == facial::KeyInterpolation::Hermite;
    }
    normaliseTrack(track);
  }
  commit("set interpolation", std::move(before));
  return {};
}

eng::Result<void> TimelineDocument::setDuration(float duration) {
  if (!std::isfinite(duration) || duration < kMinDuration)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "duration must be a number of at least " + seconds(kMinDuration));
  float last = 0.0f;
  for (const DocumentTrack& track : state_.tracks)
    if (!track.keys.empty()) last = std::max(last, track.keys.back().key.time);
  if (last > duration)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "keys lie up to " + seconds(last) + ", after the new end " + seconds(duration) +
                          " (move or delete them first)");
  State before = state_;
  state_.duration = duration;
  commit("set duration", std::move(before));
  return {};
}

eng::Result<void> TimelineDocument::setLoop(facial::LoopMode loop) {
  if (loop == state_.loop) return {};
  State before = state_;
  state_.loop = loop;
  commit("set loop", std::move(before));
  return {};
}

void TimelineDocument::beginMove() {
  if (!moveStart_) moveStart_ = state_;
}

bool TimelineDocument::moveSelected(float dt, float dv) {
  if (!moveStart_ || !std::isfinite(dt) || !std::isfinite(dv)) return false;
  // Rigid in time: clamp dt so the whole selection stays inside [0, duration].
  float first = state_.duration, last = 0.0f;
  bool any = false;
  for (const DocumentTrack& track : moveStart_->tracks)
    for (const DocumentKey& k : track.keys)
      if (isSelected(k.id)) {
        first = std::min(first, k.key.time);
        last = std::max(last, k.key.time);
        any = true;
      }
  if (!any) return false;
  dt = std::clamp(dt, -first, moveStart_->duration - last);
  state_.tracks = moveStart_->tracks;
  for (DocumentTrack& track : state_.tracks) {
    bool touched = false;
    for (DocumentKey& k : track.keys)
      if (isSelected(k.id)) {
        k.key.time += dt;
        k.key.value += dv;
        touched = true;
      }
    if (touched) normaliseTrack(track);
  }
  ++revision_;
  return true;
}

void TimelineDocument::endMove() {
  if (!moveStart_) return;
  State before = std::move(*moveStart_);
  moveStart_.reset();
  bool changed = before.tracks.size() != state_.tracks.size();
  for (size_t t = 0; !changed && t < state_.tracks.size(); ++t) {
    const auto& a = before.tracks[t].keys;
    const auto& b = state_.tracks[t].keys;
    changed = a.size() != b.size();
    for (size_t i = 0; !changed && i < a.size(); ++i)
      changed = a[i].id != b[i].id || a[i].key.time != b[i].key.time || a[i].key.value != b[i].key.value;
  }
  if (changed) commit("move keys", std::move(before));
}

void TimelineDocument::cancelMove() {
  if (!moveStart_) return;
  state_ = std::move(*moveStart_);
  moveStart_.reset();
  ++revision_;
}

eng::Result<void> TimelineDocument::moveSelectedBy(float dt, float dv) {
  if (selection_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no keys selected");
  if (!std::isfinite(dt) || !std::isfinite(dv)) return eng::makeError(eng::ErrorKind::InvalidArgument, "move by non-finite amounts");
  beginMove();
  moveSelected(dt, dv);
  endMove();
  return {};
}

bool TimelineDocument::undo() {
  if (moving() || undo_.empty()) return false;
  UndoStep step = std::move(undo_.back());
  undo_.pop_back();
  std::swap(step.before, state_);
  redo_.push_back(std::move(step));
  ++revision_;
  dropStaleSelection();
  return true;
}

bool TimelineDocument::redo() {
  if (moving() || redo_.empty()) return false;
  UndoStep step = std::move(redo_.back());
  redo_.pop_back();
  std::swap(step.before, state_);
  undo_.push_back(std::move(step));
  ++revision_;
  dropStaleSelection();
  return true;
}

}  // namespace editor
