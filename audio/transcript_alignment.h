#pragma once
// Forced alignment of an English recording with its transcript
// (pocketsphinx 5prealpha, the US English model of pocketsphinx-en-us): when
// each phoneme and word of a known text is spoken, for lip sync on recorded
// speech. Each word's pronunciation comes from the model's CMU dictionary;
// the phonemes are aligned one by one (a grammar of the phoneme sequence, each
// phoneme a one-phone "word", silences allowed between them), and each word
// spans its phonemes. Phonemes come as IPA (from ARPAbet).
#include <span>
#include <string_view>
#include <vector>

#include "audio/speech_synthesis.h"
#include "engine/core/result.h"

namespace audio {

inline constexpr double kMaxAlignSeconds = 10 * 60;  // longer recordings: split them
inline constexpr size_t kMaxAlignWords = 5000;

struct TranscriptAlignment {
  std::vector<TimedPhoneme> phonemes;  // IPA, in order, seconds from the first sample
  std::vector<TimedWord> words;        // lower-case, as looked up in the dictionary
};

// samples: mono -1..1 at sampleRate (resampled to the model's 16 kHz);
// text: English words (letters and apostrophes; numbers must be written as
// words). Errors: a word not in the dictionary (named), empty or over-long
// input, the model missing, a recording that does not fit the text.
// Decoders are independent, but sphinxbase's logging is global: calls run
// one at a time (a process-wide mutex).
eng::Result<TranscriptAlignment> alignTranscript(std::span<const float> samples, int sampleRate, std::string_view text);

// ARPAbet (CMU dictionary, stress digits ignored) as IPA, e.g. "AY" -> "aɪ"; empty if unknown.
std::string_view arpabetToIpa(std::string_view arpabet);

}  // namespace audio
