#pragma once
// Video files with sound, for a presenter's output: MP4 (H.264 through
// libx264 + AAC) or WebM (VP9 + Opus), chosen by the extension. Program-only:
// libavcodec's H.264 encoder is x264, GPL-2. Frames go to "<path>.partial"
// first and are renamed to `path` by finish(): a run that stops early (an
// error, a lost device) leaves no half-written video.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "engine/core/result.h"

namespace audio {

// Longer soundtracks are refused (the writer keeps a resampled copy).
inline constexpr double kMaxSoundtrackSeconds = 30 * 60;

struct VideoSettings {
  int width = 0, height = 0;  // even, 16..8192 (4:2:0 chroma halves both)
  float framesPerSecond = 30; // 1..240
  // The soundtrack, mono -1..1, starting with the first frame (may be empty:
  // a video without sound). All of it is written, even past the last frame.
  std::span<const float> audioSamples;
  int audioSampleRate = 0;    // 8000..192000 when there are samples
};

class VideoWriter {
 public:
  static eng::Result<VideoWriter> create(const std::filesystem::path& path, const VideoSettings& settings);
  VideoWriter(VideoWriter&&) noexcept;
  VideoWriter& operator=(VideoWriter&&) noexcept;
  ~VideoWriter();  // without finish(): closes and removes the partial file

  // rgba8: width * height * 4 bytes, row 0 at the top (alpha ignored). Copied
  // and queued: the writer's own thread converts and encodes it while the
  // caller renders the next one (at most 3 frames wait; then this blocks). An
  // encoding error comes back from the next addFrame() or from finish().
  eng::Result<void> addFrame(std::span<const uint8_t> rgba8);
  // Writes the rest of the sound, closes the file and moves it to `path`.
  eng::Result<void> finish();

 private:
  struct Impl;
  explicit VideoWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace audio
