#pragma once
// An audio-only mouth drive: from a recording alone, the mouth opens on each
// syllable and rests in silence. The energy of the voice band (300-3000 Hz,
// where vowels carry their power) is measured every 10 ms and smoothed; its
// peaks are syllable nuclei (vowels), the valleys between them consonants,
// and long stretches far below the loudest part are silence.
#include <span>
#include <vector>

#include "engine/core/result.h"

namespace audio {

enum class MouthState {
  Open,    // around a syllable nucleus: the vowel
  Closed,  // inside speech, between nuclei: consonants, short stops
  Rest,    // silence (at least kMinRestSeconds): the mouth at rest
};

inline constexpr double kMinRestSeconds = 0.12;

struct MouthSegment {
  MouthState state = MouthState::Rest;
  double start = 0, end = 0;  // seconds
  float openness = 0;         // Open: how wide, 0..1, from the nucleus' loudness; 0 otherwise
};

struct SyllableEnvelope {
  std::vector<MouthSegment> segments;  // contiguous from 0 to the end of the audio
  std::vector<double> nuclei;          // the syllable peaks, seconds
  float framesPerSecond = 0;
  std::vector<float> mouthOpen;        // per output frame (frame i at i / fps), 0 rest .. 1 wide open
};

// samples: mono, -1..1 (non-finite ones count as 0); sampleRate 1000..384000 Hz;
// framesPerSecond 1..1000 for mouthOpen. Time and memory are linear in the samples.
eng::Result<SyllableEnvelope> syllableEnvelope(std::span<const float> samples, int sampleRate, float framesPerSecond);

}  // namespace audio
