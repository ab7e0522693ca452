#pragma once
// Recording what a pad or slider does to the face as timeline keys. While
// recording, every frame samples the value of each channel on screen; on stop,
// the channels that moved become tracks whose keys are the samples reduced by
// curve simplification (Ramer-Douglas-Peucker): the linear curve through the
// kept keys stays within `tolerance` of every sample, so a gesture becomes a
// few keys per second, not one per frame. When a channel still needs more than
// `maxKeysPerSecond`, the tolerance doubles until it fits.
#include <span>
#include <string>
#include <vector>

#include "editor/timeline_document.h"
#include "engine/core/result.h"
#include "facial/runtime/curves/keyframe.h"

namespace editor {

struct RecordedTrack {
  std::string channel;
  std::vector<facial::Keyframe> keys;  // linear, times from the recording's start time
  float tolerance = 0.0f;              // the keys are within this of every frame (raised to fit the key rate)
};

struct RecordingSummary {
  size_t tracks = 0, keys = 0, samples = 0;
  float seconds = 0.0f;
};

class KeyRecorder {
 public:
  struct Options {
    float tolerance = 0.01f;        // weight units
    float maxKeysPerSecond = 6.0f;  // per track
  };

  KeyRecorder() = default;
  explicit KeyRecorder(Options options) : options_(options) {}

  // Starts a recording of these channels at `startTime` (timeline seconds).
  void start(std::vector<std::string> channels, float startTime);
  bool recording() const { return recording_; }
  const std::vector<std::string>& channels() const { return channels_; }
  // One frame: `values` per channel (in start()'s order) `elapsed` seconds after the start.
  // Frames out of order, with the wrong count or a value that is not finite are skipped.
  void sample(float elapsed, std::span<const float> values);
  // Ends the recording: the moved channels' reduced keys, their times from startTime.
  std::vector<RecordedTrack> stop();
  float startTime() const { return startTime_; }
  size_t sampleCount() const { return times_.size(); }

  // The indices of the samples kept within `tolerance` (first and last always).
  static std::vector<size_t> simplify(std::span<const float> times, std::span<const float> values, float tolerance);

 private:
  RecordedTrack reduce(std::string channel, std::span<const float> values) const;

  Options options_;
  bool recording_ = false;
  float startTime_ = 0.0f;
  std::vector<std::string> channels_;
  std::vector<float> times_;
  std::vector<float> values_;  // sample-major: channels_.size() per sample
};

// Writes the recorded keys into the document (tracks added where missing, the
// clip lengthened to hold them), replacing its keys in the recorded span.
eng::Result<RecordingSummary> writeRecording(TimelineDocument& document, std::span<const RecordedTrack> tracks,
                                             size_t samples);

}  // namespace editor
