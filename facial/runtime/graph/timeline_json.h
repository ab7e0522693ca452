#pragma once
// Timeline files (data/timelines/*.json), version 1:
//   {"version": 1, "name": "talk", "duration": 2.0, "loop": "loop",
//    "tracks": [{"channel": "AU26_JawDrop", "interpolation": "cosine",
//                "keys": [[0, 0], [0.25, 0.6], {"t": 0.5, "v": 0, "interp": "hermite", "in": 0, "out": -1}]}]}
// A key's "tangent" (auto, smooth, flat, broken) says where its slopes come from
// (curve_json.h); files without it keep "in" / "out" as written.
// "channels" ("actionUnits" or "targets", optional) says what the track names
// stand for when the file is played on its own (`facial play`; a graph's own
// "channels" decide for the timelines it holds): `facial timeline import`
// writes "targets", so a face whose targets are named like action units gets
// its weights as they are, not mapped through its rig a second time.
// "duration" defaults to the last key time, "loop" (once|clamp, loop, pingpong)
// to once, "interpolation" (a track's default per key) to linear.
#include <filesystem>
#include <string>

#include "engine/core/result.h"
#include "facial/runtime/graph/timeline.h"
#include "facial/runtime/json/json_document.h"

namespace facial {

inline constexpr int kTimelineFileVersion = 1;

// Errors read "file: /tracks/2/keys/3: problem".
eng::Result<Timeline> loadTimeline(const std::filesystem::path& path);
// A timeline object (without "version" when inline in a graph); a missing
// "name" becomes defaultName. Errors read "/tracks/2/keys/3: problem".
eng::Result<Timeline> timelineFromJson(const Json& timeline, std::string defaultName);

Json timelineToJson(const Timeline& timeline);
eng::Result<void> saveTimeline(const Timeline& timeline, const std::filesystem::path& path);

}  // namespace facial
