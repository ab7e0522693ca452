#pragma once
// A timeline clip: one keyframe track per channel, keys of all tracks in one
// sorted-per-track flat array. Immutable once built; playback state (time,
// one cursor per track) lives with whoever plays it.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/core/result.h"
#include "facial/runtime/curves/keyframe.h"

namespace facial {

enum class LoopMode : uint8_t {
  Once,      // clamp: holds the last value after the end
  Loop,      // wraps to the start
  PingPong,  // plays forward, then backward
};

// "clamp" is read as once (both hold the last pose); once is what is written.
inline constexpr eng::EnumName<LoopMode> kLoopModeNames[] = {
    {LoopMode::Once, "once"},
    {LoopMode::Once, "clamp"},
    {LoopMode::Loop, "loop"},
    {LoopMode::PingPong, "pingpong"},
};
std::string_view loopModeName(LoopMode value);
std::optional<LoopMode> loopModeFromName(std::string_view name);

// What a timeline's track names stand for, when a player must choose how to
// drive a face with it (`facial play` of a timeline file). Needed because a
// face's own targets may be named like action units (the built-in head): its
// weights must then reach the targets as they are, not through the rig again.
enum class TimelineChannels : uint8_t {
  Unmarked,     // the player decides (all tracks action units: through the rig)
  ActionUnits,  // every track is an action unit, mapped onto targets by the rig
  Targets,      // every track is a morph target of the face, its weight as it is
};
inline constexpr eng::EnumName<TimelineChannels> kTimelineChannelsNames[] = {
    {TimelineChannels::ActionUnits, "actionUnits"},
    {TimelineChannels::Targets, "targets"},
};

// Playback time -> time inside the clip [0, duration] for `mode`.
float clipTime(LoopMode mode, float duration, float playbackTime);

struct TimelineTrack {
  std::string channel;  // channel (AU or morph target) name
  uint32_t firstKey = 0;
  uint32_t keyCount = 0;
};

struct Timeline {
  std::string name;
  float duration = 0;
  LoopMode loop = LoopMode::Once;
  TimelineChannels channels = TimelineChannels::Unmarked;
  std::vector<TimelineTrack> tracks;
  std::vector<Keyframe> keys;  // track after track

  // Appends a track owning a copy of `keys`.
  void addTrack(std::string channel, std::span<const Keyframe> trackKeys);
  std::span<const Keyframe> trackKeys(size_t track) const;
  const TimelineTrack* findTrack(std::string_view channel) const;
  // Latest key time over all tracks (0 when empty).
  float lastKeyTime() const;

  // Malformed (naming the track and key) unless: duration finite and > 0,
  // key ranges inside `keys`, each track's keys valid and within [0, duration],
  // channel names non-empty and unique.
  eng::Result<void> validate() const;
};

// Samples the tracks at clip time `time` into out[trackChannels[i]]; other
// entries of out are left alone. cursors: one per track, kept between calls
// (forward playback is O(1) per track amortised; seeks stay correct).
struct TimelineSampleJob {
  const Timeline* timeline = nullptr;
  std::span<const uint32_t> trackChannels;
  float time = 0;
  std::span<uint32_t> cursors;
  std::span<float> out;
  eng::Result<void> Validate() const;
  bool Run() const;
};

}  // namespace facial
