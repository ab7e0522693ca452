#pragma once
// Reading recorded speech (libsndfile: WAV, FLAC, OGG/Vorbis, Opus, MP3) as
// mono float samples, for the audio-only mouth drive and for playback.
#include <filesystem>
#include <span>
#include <vector>

#include "engine/core/result.h"

namespace audio {

// Longer recordings are refused (30 minutes of mono float at 48 kHz is 350 MB).
inline constexpr double kMaxAudioFileSeconds = 30 * 60;

struct AudioClip {
  std::vector<float> samples;  // mono, -1..1 (channels averaged)
  int sampleRate = 0;
  double durationSeconds() const { return sampleRate > 0 ? double(samples.size()) / sampleRate : 0.0; }
};

// Errors name the file and the problem: missing, unreadable or not audio,
// empty (no samples), longer than kMaxAudioFileSeconds. A valid silent file
// reads as zeros.
eng::Result<AudioClip> readAudioFile(const std::filesystem::path& path);

// Writes mono samples (-1..1, clipped) as a 16-bit PCM WAV: into
// PATH.partial, renamed to PATH when complete, so a failed write never
// leaves a half file under the name. Errors name the file.
eng::Result<void> writeWavFile(const std::filesystem::path& path, std::span<const float> samples, int sampleRate);

}  // namespace audio
