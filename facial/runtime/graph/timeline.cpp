#include "facial/runtime/graph/timeline.h"

#include <algorithm>
#include <cmath>

#include "engine/core/name_index.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

std::string_view loopModeName(LoopMode value) { return eng::nameOf(kLoopModeNames, value); }

std::optional<LoopMode> loopModeFromName(std::string_view name) { return eng::valueNamed(kLoopModeNames, name); }

float clipTime(LoopMode mode, float duration, float playbackTime) {
  if (!(duration > 0.0f)) return 0.0f;
  switch (mode) {
    case LoopMode::Once: return std::clamp(playbackTime, 0.0f, duration);
    case LoopMode::Loop: {
      const float t = std::fmod(playbackTime, duration);
      return t < 0.0f ? t + duration : t;
    }
    case LoopMode::PingPong: {
      float t = std::fmod(playbackTime, 2.0f * duration);
      if (t < 0.0f) t += 2.0f * duration;
      return t <= duration ? t : 2.0f * duration - t;
    }
  }
  return 0.0f;
}

void Timeline::addTrack(std::string channel, std::span<const Keyframe> trackKeys) {
  tracks.push_back({std::move(channel), static_cast<uint32_t>(keys.size()), static_cast<uint32_t>(trackKeys.size())});
  keys.insert(keys.end(), trackKeys.begin(), trackKeys.end());
}

std::span<const Keyframe> Timeline::trackKeys(size_t track) const {
  const TimelineTrack& t = tracks[track];
  return std::span<const Keyframe>(keys).subspan(t.firstKey, t.keyCount);
}

const TimelineTrack* Timeline::findTrack(std::string_view channel) const {
  for (const TimelineTrack& t : tracks)
    if (t.channel == channel) return &t;
  return nullptr;
}

float Timeline::lastKeyTime() const {
  float last = 0.0f;
  for (size_t i = 0; i < tracks.size(); ++i)
    if (tracks[i].keyCount > 0) last = std::max(last, trackKeys(i).back().time);
  return last;
}

eng::Result<void> Timeline::validate() const {
  if (!std::isfinite(duration) || duration <= 0.0f)
    return eng::makeError(eng::ErrorKind::Malformed,
                          "duration must be a finite number > 0 (got " + formatNumber(duration) + ")");
  eng::NameIndex channels;  // one look-up per track: thousands of tracks stay linear
  for (size_t i = 0; i < tracks.size(); ++i) {
    const TimelineTrack& t = tracks[i];
    if (t.channel.empty())
      return eng::makeError(eng::ErrorKind::Malformed, "track " + std::to_string(i) + " has an empty channel name");
    const std::string where = "track " + std::to_string(i) + " ('" + t.channel + "')";
    if (!channels.add(t.channel, static_cast<uint32_t>(i)))
      return eng::makeError(eng::ErrorKind::Malformed,
                            where + " animates the same channel as track " + std::to_string(*channels.find(t.channel)));
    if (size_t{t.firstKey} + t.keyCount > keys.size())
      return eng::makeError(eng::ErrorKind::Malformed, where + " keys [" + std::to_string(t.firstKey) + ", " +
                                                           std::to_string(t.firstKey + t.keyCount) + ") run past the " +
                                                           std::to_string(keys.size()) + " keys");
    const std::span<const Keyframe> k = trackKeys(i);
    if (auto keysValid = validateKeys(k); !keysValid) return keysValid.error().prefixed(where + ": ");
    if (k.front().time < 0.0f || k.back().time > duration)
      return eng::makeError(eng::ErrorKind::Malformed, where + ": key times [" + formatNumber(k.front().time) + ", " +
                                                           formatNumber(k.back().time) + "] leave the clip [0, " +
                                                           formatNumber(duration) + "]");
  }
  return {};
}

eng::Result<void> TimelineSampleJob::Validate() const {
  if (!timeline) return eng::makeError(eng::ErrorKind::InvalidArgument, "TimelineSampleJob: no timeline");
  const size_t tracks = timeline->tracks.size();
  if (trackChannels.size() != tracks || cursors.size() != tracks)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "TimelineSampleJob: timeline '" + timeline->name + "' has " + std::to_string(tracks) +
                              " tracks, " + std::to_string(trackChannels.size()) + " channel indices and " +
                              std::to_string(cursors.size()) + " cursors given");
  for (uint32_t c : trackChannels)
    if (c >= out.size())
      return eng::makeError(eng::ErrorKind::InvalidArgument, "TimelineSampleJob: channel index " + std::to_string(c) +
                                                                 " outside the pose of " + std::to_string(out.size()));
  if (!std::isfinite(time))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "TimelineSampleJob: time is not finite");
  return {};
}

bool TimelineSampleJob::Run() const {
  if (!Validate().ok()) return false;
  for (size_t i = 0; i < trackChannels.size(); ++i)
    out[trackChannels[i]] = sampleKeys(timeline->trackKeys(i), time, cursors[i]);
  return true;
}

}  // namespace facial
