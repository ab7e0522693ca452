#pragma once
// IPA phonemes -> visemes. A phoneme is one symbol string as espeak-ng
// (`--ipa`) or a forced aligner writes it: "t", "tʃ", "aɪ", "ˈaː", "ɔ̃",
// "t̪", "aː2" (a Vietnamese tone number). Stress, length, syllable and tie
// marks, combining diacritics (nasalisation, dental, ...) and tone numbers and
// letters are stripped; what is left is mapped symbol by symbol. A diphthong
// gives two visemes, its start and its end.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/speech/viseme.h"

namespace facial {

struct PhonemeVisemes {
  enum class Kind : uint8_t {
    Shaped,       // visemes[0..count) in order
    Silence,      // a pause label ("", "_", "sil", "sp", "pau")
    Transparent,  // no mouth shape of its own (h, ʔ): it takes its neighbour's
  };
  Kind kind = Kind::Shaped;
  std::array<Viseme, 2> visemes{};
  uint8_t count = 0;  // 1, or 2 for a diphthong (Shaped only)
};

// The visemes of one phoneme; nullopt when no symbol in it can be mapped,
// not even by its base letter (the builder reports those).
std::optional<PhonemeVisemes> visemesForIpa(std::string_view phoneme);

// An IPA transcription ("ɡˈʊd ˈiːvnɪŋ", espeak-ng --ipa output) cut into
// phonemes: one per base symbol, the symbol pairs that make one sound (tʃ, dʒ,
// ts, the diphthongs aɪ, oʊ, iə, ...) and symbols tied with U+0361 or
// U+200D (espeak-ng --ipa=3) kept together, marks kept on their phoneme,
// spaces and punctuation dropped.
std::vector<std::string> splitIpa(std::string_view transcription);

}  // namespace facial
