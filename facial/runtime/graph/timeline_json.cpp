#include "facial/runtime/graph/timeline_json.h"

#include <fstream>

#include "engine/core/name_index.h"

#include "facial/runtime/graph/curve_json.h"
#include "facial/runtime/graph/detail/json_reader.h"
#include "facial/runtime/graph/weight_range.h"
#include "facial/runtime/rig/action_units.h"

namespace facial {

namespace {

// One track: {"channel", "interpolation", "keys"}, added to `timeline`;
// `channels` holds the channels of the tracks read so far.
eng::Result<void> parseTrack(const JsonNode& track, Timeline& timeline, eng::NameIndex& channels) {
  ENG_TRY(track.allowOnly({"channel", "interpolation", "keys"}));
  const JsonNode channelNode = ENG_TRY_VALUE(track.at("channel"));
  const std::string channel = ENG_TRY_VALUE(channelNode.string());
  if (channel.empty()) return channelNode.error("empty channel name");
  if (!channels.add(channel, static_cast<uint32_t>(timeline.tracks.size())))
    return channelNode.error("channel '" + channel + "' already has a track");
  KeyInterpolation interp = KeyInterpolation::Linear;
  if (auto d = track.find("interpolation")) interp = ENG_TRY_VALUE(detail::parseKeyInterpolation(*d));
  const JsonNode keysNode = ENG_TRY_VALUE(track.at("keys"));
  const std::vector<Keyframe> keys = ENG_TRY_VALUE(detail::parseKeyframes(keysNode, interp));
  if (keys.front().time < 0.0f) return keysNode.element(0).error("key time is negative");
  for (size_t k = 0; k < keys.size(); ++k)
    if (!isWeightInRange(keys[k].value)) return keysNode.element(k).error(weightRangeProblem(keys[k].value));
  timeline.addTrack(channel, keys);
  return {};
}

}  // namespace

eng::Result<Timeline> detail::parseTimeline(const JsonNode& node, std::string defaultName) {
  ENG_TRY(node.allowOnly({"version", "name", "duration", "loop", "channels", "tracks"}));
  Timeline timeline;
  timeline.name = ENG_TRY_VALUE(node.stringOr("name", std::move(defaultName)));
  if (auto loop = node.find("loop")) {
    const std::string name = ENG_TRY_VALUE(loop->string());
    auto mode = loopModeFromName(name);
    if (!mode) return loop->error("unknown loop mode '" + name + "' (expected " + eng::nameList(kLoopModeNames) + ")");
    timeline.loop = *mode;
  }
  const JsonNode tracks = ENG_TRY_VALUE(node.at("tracks"));
  const size_t trackCount = ENG_TRY_VALUE(tracks.size());
  eng::NameIndex channels;
  for (size_t i = 0; i < trackCount; ++i) ENG_TRY(parseTrack(tracks.element(i), timeline, channels));
  if (auto mark = node.find("channels")) {
    const std::string name = ENG_TRY_VALUE(mark->string());
    const auto kind = eng::valueNamed(kTimelineChannelsNames, name);
    if (!kind) return mark->error("unknown channels '" + name + "' (expected " + eng::nameList(kTimelineChannelsNames) + ")");
    timeline.channels = *kind;
    if (*kind == TimelineChannels::ActionUnits)
      for (size_t i = 0; i < timeline.tracks.size(); ++i)
        if (!actionUnitIndex(timeline.tracks[i].channel))
          return tracks.element(i).error("channel '" + timeline.tracks[i].channel +
                                         "' is not an action unit (the file says \"channels\": \"actionUnits\")");
  }
  if (auto d = node.find("duration")) {
    timeline.duration = ENG_TRY_VALUE(d->number());
    if (timeline.duration <= 0.0f) return d->error("duration must be > 0");
    if (timeline.lastKeyTime() > timeline.duration)
      return d->error("duration " + formatNumber(timeline.duration) + " ends before the last key at " +
                      formatNumber(timeline.lastKeyTime()));
  } else {
    timeline.duration = timeline.lastKeyTime();
    if (timeline.duration <= 0.0f) return node.error("no \"duration\" and every key is at time 0");
  }
  if (auto valid = timeline.validate(); !valid) return node.error(valid.error());
  return timeline;
}

eng::Result<Timeline> loadTimeline(const std::filesystem::path& path) {
  auto document = readJsonFile(path);
  if (!document) return document.error();
  auto timeline = [&]() -> eng::Result<Timeline> {
    const JsonNode root(*document, "");
    ENG_TRY(requireVersion(root, kTimelineFileVersion));
    ENG_TRY(detail::checkNumberRange(root));
    return detail::parseTimeline(root, path.stem().string());
  }();
  if (!timeline) return timeline.error().prefixed(path.string() + ": ");
  return timeline;
}

eng::Result<Timeline> timelineFromJson(const Json& timeline, std::string defaultName) {
  const JsonNode root(timeline, "");
  ENG_TRY(detail::checkNumberRange(root));
  return detail::parseTimeline(root, std::move(defaultName));
}

Json timelineToJson(const Timeline& timeline) {
  Json tracks = Json::array();
  for (size_t i = 0; i < timeline.tracks.size(); ++i) {
    const std::span<const Keyframe> keys = timeline.trackKeys(i);
    const KeyInterpolation interp = keys.empty() ? KeyInterpolation::Linear : keys.front().interpolation;
    tracks.push_back({{"channel", timeline.tracks[i].channel},
                      {"interpolation", keyInterpolationName(interp)},
                      {"keys", keyframesToJson(keys, interp)}});
  }
  Json out = {{"version", kTimelineFileVersion},
              {"name", timeline.name},
              {"duration", detail::jsonNumber(timeline.duration)},
              {"loop", loopModeName(timeline.loop)}};
  if (timeline.channels != TimelineChannels::Unmarked)
    out["channels"] = std::string(eng::nameOf(kTimelineChannelsNames, timeline.channels));
  out["tracks"] = std::move(tracks);
  return out;
}

eng::Result<void> saveTimeline(const Timeline& timeline, const std::filesystem::path& path) {
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed(path.string() + ": timeline not saved: ");
  std::ofstream out(path, std::ios::binary);
  if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot write timeline file");
  out << timelineToJson(timeline).dump(1) << '\n';
  if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": write failed");
  return {};
}

}  // namespace facial
