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

// The runtime's own tangent rule over the document's keys (one home: facial/runtime/curves).
void resolveTrackTangents(std::vector<DocumentKey>& keys) {
  std::vector<facial::Keyframe> plain(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) plain[i] = keys[i].key;
  facial::resolveTangents(plain);
  for (size_t i = 0; i < keys.size(); ++i) keys[i].key = plain[i];
}

bool sameKeys(const std::vector<DocumentKey>& a, const std::vector<DocumentKey>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const facial::Keyframe &x = a[i].key, &y = b[i].key;
    if (a[i].id != b[i].id || x.time != y.time || x.value != y.value || x.inTangent != y.inTangent ||
        x.outTangent != y.outTangent || x.tangent != y.tangent)
      return false;
  }
  return true;
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
    for (const facial::Keyframe& k : timeline.trackKeys(t)) track.keys.push_back({doc.nextId_++, k});
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
  resolveTrackTangents(keys);
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
    k.tangent = facial::TangentMode::Auto;  // new keys: smooth through their neighbours when cubic
    keys.push_back({id, k});
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
      // Turning a key cubic gives it auto tangents (a loaded key's slopes stay until then).
      if (interpolation == facial::KeyInterpolation::Hermite && k.key.interpolation != interpolation)
        k.key.tangent = facial::TangentMode::Auto;
      k.key.interpolation = interpolation;
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
  for (size_t t = 0; !changed && t < state_.tracks.size(); ++t)
    changed = !sameKeys(before.tracks[t].keys, state_.tracks[t].keys);
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

// ---- Selection gestures, clipboard, frames, mute / solo, playback (issue 34) ----

template <typename Edit>
eng::Result<void> TimelineDocument::edit(std::string label, Edit&& change) {
  State before = state_;
  if (auto done = change(); !done) {
    state_ = std::move(before);
    return done;
  }
  commit(std::move(label), std::move(before));
  return {};
}

eng::Result<void> TimelineDocument::requireSelection(std::string_view action) const {
  if (selection_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no keys selected to " + std::string(action));
  return {};
}

void TimelineDocument::selectKeys(std::span<const KeyId> ids, SelectMode mode) {
  if (mode == SelectMode::Replace) selection_.clear();
  for (KeyId id : ids) {
    if (!locate(id)) continue;
    const auto it = std::find(selection_.begin(), selection_.end(), id);
    if (it == selection_.end()) selection_.push_back(id);
    else if (mode == SelectMode::Toggle) selection_.erase(it);
  }
}

std::vector<KeyId> TimelineDocument::keysInBox(float t0, float t1, std::span<const size_t> tracks, float v0,
                                               float v1) const {
  if (t0 > t1) std::swap(t0, t1);
  if (v0 > v1) std::swap(v0, v1);
  std::vector<KeyId> ids;
  auto collect = [&](size_t t) {
    if (t >= state_.tracks.size()) return;
    for (const DocumentKey& k : state_.tracks[t].keys)
      if (k.key.time >= t0 && k.key.time <= t1 && k.key.value >= v0 && k.key.value <= v1) ids.push_back(k.id);
  };
  if (tracks.empty())
    for (size_t t = 0; t < state_.tracks.size(); ++t) collect(t);
  for (size_t t : tracks) collect(t);
  return ids;
}

void TimelineDocument::selectAtTime(float time, SelectMode mode) {
  const float half = 0.5f * frameDuration();
  selectKeys(keysInBox(time - half, time + half, {}), mode);
}

void TimelineDocument::selectAll() { selectKeys(keysInBox(0.0f, state_.duration, {}), SelectMode::Replace); }

float TimelineDocument::snapTime(float time) const { return std::round(time * state_.frameRate) / state_.frameRate; }

float TimelineDocument::playheadAt(float playTime) const {
  const PlaybackSettings& p = state_.playback;
  if (p.hasLoopRange && playTime >= p.loopStart)
    return p.loopStart + facial::clipTime(facial::LoopMode::Loop, p.loopEnd - p.loopStart, playTime - p.loopStart);
  return facial::clipTime(state_.loop, state_.duration, playTime);
}

bool TimelineDocument::audible(size_t track) const {
  if (track >= state_.tracks.size() || state_.tracks[track].muted) return false;
  const bool anySolo = std::any_of(state_.tracks.begin(), state_.tracks.end(), [](const DocumentTrack& t) { return t.solo; });
  return !anySolo || state_.tracks[track].solo;
}

eng::Result<void> TimelineDocument::setKeyShape(KeyId id, facial::KeyInterpolation interpolation, facial::TangentMode tangent,
                                                std::optional<float> inSlope, std::optional<float> outSlope) {
  const auto where = locate(id);
  if (!where) return eng::makeError(eng::ErrorKind::InvalidArgument, "no key " + std::to_string(id));
  if ((inSlope && !std::isfinite(*inSlope)) || (outSlope && !std::isfinite(*outSlope)))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "tangent slopes must be finite numbers");
  return edit("set tangent", [&]() -> eng::Result<void> {
    DocumentTrack& track = state_.tracks[where->track];
    facial::Keyframe& k = track.keys[where->index].key;
    k.interpolation = interpolation;
    k.tangent = tangent;
    if (inSlope) k.inTangent = *inSlope;
    if (outSlope) k.outTangent = *outSlope;
    normaliseTrack(track);
    return {};
  });
}

bool TimelineDocument::dragTangent(KeyId id, float inSlope, float outSlope, bool breakTangent) {
  const auto where = locate(id);
  if (!moveStart_ || !where || !std::isfinite(inSlope) || !std::isfinite(outSlope)) return false;
  DocumentTrack& track = state_.tracks[where->track];
  facial::Keyframe& k = track.keys[where->index].key;
  if (breakTangent || k.tangent == facial::TangentMode::Broken) {
    k.tangent = facial::TangentMode::Broken;
    k.inTangent = inSlope;
  } else {
    k.tangent = facial::TangentMode::Smooth;
  }
  k.outTangent = outSlope;
  k.interpolation = facial::KeyInterpolation::Hermite;
  normaliseTrack(track);
  ++revision_;
  return true;
}

eng::Result<void> TimelineDocument::keyExclusive(const std::string& channel, std::span<const std::string_view> group, float time,
                                                 facial::KeyInterpolation interpolation, facial::TangentMode tangent) {
  if (std::find(group.begin(), group.end(), channel) == group.end())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "'" + channel + "' is not one of the channels keyed together");
  if (!std::isfinite(time) || time < 0.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "key time must be a number >= 0");
  auto inGroup = [&](const DocumentTrack& t) { return std::find(group.begin(), group.end(), t.channel) != group.end(); };
  std::vector<KeyId> keyed;
  return edit("key " + channel, [&]() -> eng::Result<void> {
    state_.duration = std::max(state_.duration, time);  // keying past the end grows the clip
    if (!findTrack(channel)) {
      DocumentTrack fresh{channel, {}};
      for (const DocumentTrack& t : state_.tracks)  // 0 wherever the group was keyed before
        if (inGroup(t))
          for (const DocumentKey& k : t.keys)
            if (k.key.time < time) fresh.keys.push_back({nextId_++, {.time = k.key.time, .interpolation = interpolation, .tangent = tangent}});
      state_.tracks.push_back(std::move(fresh));
    }
    for (DocumentTrack& t : state_.tracks) {
      if (!inGroup(t)) continue;
      std::erase_if(t.keys, [&](const DocumentKey& k) { return std::abs(k.key.time - time) < kMinKeySpacing; });
      const facial::Keyframe k{.time = time, .value = t.channel == channel ? 1.0f : 0.0f, .interpolation = interpolation,
                               .tangent = tangent};
      t.keys.push_back({nextId_++, k});
      keyed.push_back(t.keys.back().id);
      normaliseTrack(t);
    }
    selection_ = keyed;
    return {};
  });
}

KeyClipboard TimelineDocument::copySelection() const {
  KeyClipboard clip;
  float first = INFINITY, last = -INFINITY;
  for (const DocumentTrack& track : state_.tracks)
    for (const DocumentKey& k : track.keys)
      if (isSelected(k.id)) {
        clip.keys.push_back({track.channel, k.key});
        first = std::min(first, k.key.time);
        last = std::max(last, k.key.time);
      }
  for (KeyClipboard::Entry& e : clip.keys) e.key.time -= first;
  clip.span = clip.keys.empty() ? 0.0f : last - first;
  return clip;
}

eng::Result<void> TimelineDocument::paste(const KeyClipboard& clipboard, float time) {
  if (clipboard.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "nothing copied to paste");
  if (!std::isfinite(time) || time < 0.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "paste time must be a number >= 0");
  std::vector<KeyId> pasted;
  auto result = edit("paste keys", [&]() -> eng::Result<void> {
    state_.duration = std::max(state_.duration, time + clipboard.span);  // the clip grows to hold them
    for (const KeyClipboard::Entry& e : clipboard.keys) {
      auto track = findTrack(e.channel);
      if (!track) {
        state_.tracks.push_back({e.channel, {}});
        track = state_.tracks.size() - 1;
      }
      DocumentKey k{nextId_++, e.key};
      k.key.time += time;
      state_.tracks[*track].keys.push_back(k);
      pasted.push_back(k.id);
    }
    selection_ = pasted;  // pasted keys win over keys already at those times
    for (DocumentTrack& track : state_.tracks) normaliseTrack(track);
    return {};
  });
  return result;
}

eng::Result<void> TimelineDocument::duplicateSelected() {
  ENG_TRY(requireSelection("duplicate"));
  const KeyClipboard clip = copySelection();
  float first = INFINITY;
  for (KeyId id : selection_) first = std::min(first, key(id)->key.time);
  return paste(clip, first + clip.span + frameDuration());
}

eng::Result<void> TimelineDocument::nudgeSelected(int frames) {
  ENG_TRY(requireSelection("nudge"));
  return moveSelectedBy(float(frames) * frameDuration(), 0.0f);
}

eng::Result<void> TimelineDocument::snapToFrames(float framesPerSecond) {
  if (!std::isfinite(framesPerSecond) || framesPerSecond < 1.0f || framesPerSecond > 1000.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "frame rate must be 1 to 1000 frames a second");
  return edit("snap to frames", [&]() -> eng::Result<void> {
    state_.frameRate = framesPerSecond;
    const bool all = selection_.empty();
    for (DocumentTrack& track : state_.tracks) {
      for (DocumentKey& k : track.keys)
        if (all || isSelected(k.id)) k.key.time = std::min(snapTime(k.key.time), state_.duration);
      normaliseTrack(track);
    }
    return {};
  });
}

eng::Result<void> TimelineDocument::setMuted(size_t track, bool muted) {
  if (track >= state_.tracks.size()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no track " + std::to_string(track));
  return edit(muted ? "mute track" : "unmute track", [&]() -> eng::Result<void> {
    state_.tracks[track].muted = muted;
    return {};
  });
}

eng::Result<void> TimelineDocument::setSolo(size_t track, bool solo) {
  if (track >= state_.tracks.size()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no track " + std::to_string(track));
  return edit(solo ? "solo track" : "unsolo track", [&]() -> eng::Result<void> {
    state_.tracks[track].solo = solo;
    return {};
  });
}

eng::Result<void> TimelineDocument::setLoopRange(float start, float end) {
  if (!std::isfinite(start) || !std::isfinite(end) || start < 0.0f || end > state_.duration ||
      end - start < frameDuration() * 0.999f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "loop range " + seconds(start) + " to " + seconds(end) +
                                                               " must lie in the clip [0, " + seconds(state_.duration) +
                                                               "] and be at least a frame long");
  return edit("set loop range", [&]() -> eng::Result<void> {
    state_.playback.hasLoopRange = true;
    state_.playback.loopStart = start;
    state_.playback.loopEnd = end;
    return {};
  });
}

eng::Result<void> TimelineDocument::clearLoopRange() {
  if (!state_.playback.hasLoopRange) return {};
  return edit("clear loop range", [&]() -> eng::Result<void> {
    state_.playback.hasLoopRange = false;
    return {};
  });
}

eng::Result<void> TimelineDocument::setSpeed(float speed) {
  if (!std::isfinite(speed) || speed < 0.05f || speed > 20.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "playback speed must be 0.05 to 20");
  return edit("set speed", [&]() -> eng::Result<void> {
    state_.playback.speed = speed;
    return {};
  });
}

}  // namespace editor

namespace editor {

TimelineSettings TimelineDocument::settings() const {
  TimelineSettings s{.frameRate = state_.frameRate, .playback = state_.playback};
  for (const DocumentTrack& track : state_.tracks) {
    if (track.muted) s.muted.push_back(track.channel);
    if (track.solo) s.solo.push_back(track.channel);
  }
  return s;
}

void TimelineDocument::restoreSettings(const TimelineSettings& s) {
  if (std::isfinite(s.frameRate) && s.frameRate >= 1.0f && s.frameRate <= 1000.0f) state_.frameRate = s.frameRate;
  if (std::isfinite(s.playback.speed) && s.playback.speed >= 0.05f && s.playback.speed <= 20.0f) state_.playback.speed = s.playback.speed;
  const PlaybackSettings& p = s.playback;
  const bool loopFits = p.hasLoopRange && std::isfinite(p.loopStart) && std::isfinite(p.loopEnd) && p.loopStart >= 0.0f &&
                        p.loopEnd <= state_.duration && p.loopEnd > p.loopStart;
  state_.playback.hasLoopRange = loopFits;
  if (loopFits) {
    state_.playback.loopStart = p.loopStart;
    state_.playback.loopEnd = p.loopEnd;
  }
  for (DocumentTrack& track : state_.tracks) {
    track.muted = std::find(s.muted.begin(), s.muted.end(), track.channel) != s.muted.end();
    track.solo = std::find(s.solo.begin(), s.solo.end(), track.channel) != s.solo.end();
  }
  ++revision_;  // players re-sample; serial (dirty) unchanged
}

}  // namespace editor
