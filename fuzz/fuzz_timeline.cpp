// Timeline files (data/timelines/*.json). A timeline that loads must
// validate (the player relies on it) and sample to finite values anywhere,
// played forward and seeked.
#include <cmath>
#include <string>
#include <vector>

#include "facial/runtime/graph/timeline_json.h"
#include "fuzz/fuzz_support.h"
#include "fuzz/json_growth.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = fuzz::writeInput("timeline.json", data, size);
  auto timeline = facial::loadTimeline(path);
  if (!timeline) return 0;
  const auto valid = timeline->validate();
  FUZZ_PROPERTY(valid.ok(), "a loaded timeline does not validate: " + valid.error().message);
  const size_t tracks = timeline->tracks.size();
  std::vector<uint32_t> channels(tracks), cursors(tracks, 0);
  for (size_t i = 0; i < tracks; ++i) channels[i] = uint32_t(i);
  std::vector<float> out(tracks, 0.0f);
  for (float t : {0.0f, 0.01f, 0.5f, 1.0f, 0.2f, 1e9f, -1.0f, 0.75f}) {
    const float clip = facial::clipTime(timeline->loop, timeline->duration, t * timeline->duration);
    facial::TimelineSampleJob job{&*timeline, channels, clip, cursors, out};
    FUZZ_PROPERTY(job.Run(), "sampling a valid timeline failed: " + job.Validate().error().message);
    for (float v : out) FUZZ_PROPERTY(std::isfinite(v), "sampled " + std::to_string(v) + " at " + std::to_string(clip));
  }
  return 0;
}

// Larger graphs and timelines than byte mutations make (fuzz/json_growth.h).
FUZZ_GROW_JSON_MUTATOR
