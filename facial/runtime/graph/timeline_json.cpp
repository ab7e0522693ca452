#include "facial/runtime/graph/timeline_json.h"

#include <fstream>

#include "facial/runtime/graph/curve_json.h"
#include "facial/runtime/graph/detail/json_reader.h"

namespace facial {

Timeline detail::parseTimeline(const JsonNode& node, std::string defaultName) {
  node.allowOnly({"version", "name", "duration", "loop", "tracks"});
  Timeline timeline;
  timeline.name = node.stringOr("name", std::move(defaultName));
  if (auto loop = node.find("loop")) {
    auto mode = loopModeFromString(loop->string());
    if (!mode) loop->fail("unknown loop mode '" + loop->string() + "' (expected once, clamp, loop or pingpong)");
    timeline.loop = *mode;
  }
  const JsonNode tracks = node.at("tracks");
  for (size_t i = 0; i < tracks.size(); ++i) {
    const JsonNode track = tracks[i];
    track.allowOnly({"channel", "interpolation", "keys"});
    const std::string channel = track.at("channel").string();
    if (channel.empty()) track.at("channel").fail("empty channel name");
    if (timeline.findTrack(channel)) track.at("channel").fail("channel '" + channel + "' already has a track");
    KeyInterpolation interp = KeyInterpolation::Linear;
    if (auto d = track.find("interpolation")) interp = parseKeyInterpolation(*d);
    const std::vector<Keyframe> keys = parseKeyframes(track.at("keys"), interp);
    if (keys.front().time < 0.0f) track.at("keys")[0].fail("key time is negative");
    timeline.addTrack(channel, keys);
  }
  if (auto d = node.find("duration")) {
    timeline.duration = d->number();
    if (timeline.duration <= 0.0f) d->fail("duration must be > 0");
    if (timeline.lastKeyTime() > timeline.duration)
      d->fail("duration " + formatNumber(timeline.duration) + " ends before the last key at " +
              formatNumber(timeline.lastKeyTime()));
  } else {
    timeline.duration = timeline.lastKeyTime();
    if (timeline.duration <= 0.0f) node.fail("no \"duration\" and every key is at time 0");
  }
  if (auto valid = timeline.validate(); !valid) node.fail(valid.error());
  return timeline;
}

eng::Result<Timeline> loadTimeline(const std::filesystem::path& path) {
  auto document = readJsonFile(path);
  if (!document) return document.error();
  try {
    const detail::JsonNode root(*document, "");
    detail::requireVersion(root, kTimelineFileVersion);
    return detail::parseTimeline(root, path.stem().string());
  } catch (const detail::JsonProblem& p) {
    return detail::jsonProblemError(p, path.string());
  }
}

eng::Result<Timeline> timelineFromJson(const Json& timeline, std::string defaultName) {
  try {
    return detail::parseTimeline(detail::JsonNode(timeline, ""), std::move(defaultName));
  } catch (const detail::JsonProblem& p) {
    return detail::jsonProblemError(p, "");
  }
}

Json timelineToJson(const Timeline& timeline) {
  Json tracks = Json::array();
  for (size_t i = 0; i < timeline.tracks.size(); ++i) {
    const std::span<const Keyframe> keys = timeline.trackKeys(i);
    const KeyInterpolation interp = keys.empty() ? KeyInterpolation::Linear : keys.front().interpolation;
    tracks.push_back({{"channel", timeline.tracks[i].channel},
                      {"interpolation", toString(interp)},
                      {"keys", keyframesToJson(keys, interp)}});
  }
  return {{"version", kTimelineFileVersion},
          {"name", timeline.name},
          {"duration", detail::jsonNumber(timeline.duration)},
          {"loop", toString(timeline.loop)},
          {"tracks", std::move(tracks)}};
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
