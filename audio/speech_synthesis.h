#pragma once
// Offline text to speech with timed phonemes (espeak-ng, GPL-3: this library
// is linked by programs only, never by the component an engine embeds).
// espeak-ng keeps one global synthesiser (voice, rate, callback); every call
// into it goes through one process-wide mutex, so synthesize() is safe to call
// from several threads but runs one synthesis at a time.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace audio {

// Texts longer than this are refused: about 20 minutes of speech at the
// normal rate, 50 MB of samples (bounded memory for any caller's input).
inline constexpr size_t kMaxSpeechCharacters = 20000;
// Synthesis stops with an error past this much audio (a very slow rate on a
// long text), whatever the text length.
inline constexpr double kMaxSpeechSeconds = 30 * 60;

struct SpeechOptions {
  std::string language = "en";  // an espeak-ng voice name: "en", "fr", "vi", "en-us", ...
  float ratePercent = 100;      // speaking rate, % of espeak's normal 175 words a minute; 50..250
  float pitchPercent = 100;     // base pitch, % of the voice's normal; 0..200
};

struct TimedPhoneme {
  std::string ipa;  // one IPA phoneme, e.g. "əʊ", "t̪"
  double start = 0, end = 0;  // seconds from the first sample; espeak gives a few zero-length ones
};

struct TimedWord {
  std::string text;  // the word as written in the input
  double start = 0, end = 0;  // seconds: its first phoneme's start to its last phoneme's end
};

struct Speech {
  std::vector<int16_t> samples;  // mono PCM
  int sampleRate = 0;            // espeak-ng's rate (22050 Hz)
  std::vector<TimedPhoneme> phonemes;  // in order; gaps between them are pauses
  std::vector<TimedWord> words;
  double durationSeconds() const { return sampleRate > 0 ? double(samples.size()) / sampleRate : 0.0; }
};

// Speaks `text` (UTF-8) in options.language. The phonemes and words are the
// same from call to call; the samples vary slightly (espeak-ng's noise sources). Errors: empty or over-long text,
// rate or pitch out of range, an unknown language (the message lists a few
// known ones), espeak-ng's data missing.
eng::Result<Speech> synthesize(std::string_view text, const SpeechOptions& options = {});

// The languages espeak-ng knows (its voices' language codes, e.g. "en-gb"), sorted.
eng::Result<std::vector<std::string>> speechLanguages();

}  // namespace audio
