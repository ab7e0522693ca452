#pragma once
// A line of text made ready to speak: espeak-ng's voice (audio::synthesize)
// and the viseme track its timed phonemes build (facial::VisemeTrackBuilder),
// on the same clock. The one home of that step for `facial say` and the live
// Speak buttons of the window demo and the editor.
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "audio/speech_synthesis.h"
#include "engine/core/result.h"
#include "facial/runtime/speech/viseme_track.h"

namespace audio {

struct SpokenLine {
  std::vector<float> samples;  // mono, -1..1
  int sampleRate = 0;
  std::shared_ptr<const facial::VisemeTrack> track;  // seconds from the first sample
  std::vector<std::string> warnings;                 // phonemes the track could not map, one line each
  double seconds() const { return sampleRate > 0 ? double(samples.size()) / sampleRate : 0.0; }
};

// How an emotion shades the voice (sad slower and lower, happy and surprise
// quicker and higher): the voice for `language` with `emotion` (one of
// facial::emotionNames(); another name: unshaded) at `intensity` in [0, 1].
SpeechOptions emotionalVoice(std::string language, std::string_view emotion, float intensity = 1.0f);

// espeak-ng's phonemes as the track builder takes them, `offset` seconds
// later, appended to `out`; zero-length ones are dropped.
void appendTrackPhonemes(std::span<const TimedPhoneme> spoken, float offset, std::vector<facial::TimedPhoneme>& out);

// Errors: synthesize()'s (empty or over-long text, an unknown language, ...)
// and the track builder's, unprefixed: the caller names its argument.
eng::Result<SpokenLine> speakLine(std::string_view text, const SpeechOptions& options = {});

}  // namespace audio
