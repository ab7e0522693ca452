#include "facial/runtime/speech/ipa_visemes.h"

#include <algorithm>

#include "facial/runtime/speech/utf8_text.h"

namespace facial {
namespace {

using V = Viseme;

// What a base symbol is: a viseme, or no shape of its own.
struct SymbolClass {
  char32_t symbol;
  int8_t viseme;  // a Viseme, or kTransparent
  bool vowel;     // a syllable nucleus (diphthongs join vowels; j, w, ɥ are glides, not vowels)
};
constexpr int8_t kTransparent = -1;

constexpr SymbolClass S(char32_t c, V v, bool vowel = false) { return {c, static_cast<int8_t>(v), vowel}; }
constexpr SymbolClass Vw(char32_t c, V v) { return S(c, v, true); }

// The consonants and vowels of English, French and Vietnamese (and their IPA
// neighbours) in the Oculus classes: PP bilabials, FF labiodentals, TH
// dentals, DD alveolar stops and taps, nn nasals and laterals (Oculus puts l
// with n), kk velars, uvulars and palatal stops, CH postalveolars, SS
// sibilants, RR rhotics. Vowels by their visible shape: aa open, E mid
// unrounded (and schwa), I close unrounded, O mid/open rounded, U close
// rounded (the French front rounded y, ø, œ round like u and o).
constexpr SymbolClass kSymbols[] = {
    S(U'p', V::PP),  S(U'b', V::PP),  S(U'm', V::PP),  S(U'ɓ', V::PP),  S(U'ʙ', V::PP),  S(U'f', V::FF),  S(U'v', V::FF),
    S(U'ɸ', V::FF),  S(U'β', V::FF),  S(U'ʋ', V::FF),  S(U'ɱ', V::FF),  S(U'θ', V::TH),  S(U'ð', V::TH),  S(U't', V::DD),
    S(U'd', V::DD),  S(U'ɗ', V::DD),  S(U'ʈ', V::DD),  S(U'ɖ', V::DD),  S(U'ɾ', V::DD),  S(U'ɽ', V::DD),  S(U'ɬ', V::DD),
    S(U'ɮ', V::DD),  S(U'n', V::nn),  S(U'ɲ', V::nn),  S(U'ŋ', V::nn),  S(U'ɳ', V::nn),  S(U'ɴ', V::nn),  S(U'l', V::nn),
    S(U'ɫ', V::nn),  S(U'ɭ', V::nn),  S(U'ʎ', V::nn),  S(U'ʟ', V::nn),  S(U'k', V::kk),  S(U'g', V::kk),  S(U'ɡ', V::kk),
    S(U'x', V::kk),  S(U'ɣ', V::kk),  S(U'q', V::kk),  S(U'ɢ', V::kk),  S(U'χ', V::kk),  S(U'ɠ', V::kk),  S(U'c', V::kk),
    S(U'ɟ', V::kk),  S(U'ʃ', V::CH),  S(U'ʒ', V::CH),  S(U'ɕ', V::CH),  S(U'ʑ', V::CH),  S(U'ʂ', V::CH),  S(U'ʐ', V::CH),
    S(U'ç', V::CH),  S(U'ʝ', V::CH),  S(U's', V::SS),  S(U'z', V::SS),  S(U'r', V::RR),  S(U'ɹ', V::RR),  S(U'ɻ', V::RR),
    S(U'ʁ', V::RR),  S(U'ʀ', V::RR),  S(U'j', V::I),   S(U'w', V::U),   S(U'ɥ', V::U),   S(U'ʍ', V::U),   Vw(U'a', V::aa),
    Vw(U'ɑ', V::aa), Vw(U'ɐ', V::aa), Vw(U'æ', V::aa), Vw(U'ʌ', V::aa), Vw(U'ä', V::aa), Vw(U'ɶ', V::aa), Vw(U'e', V::E),
    Vw(U'ɛ', V::E),  Vw(U'ə', V::E),  Vw(U'ɜ', V::E),  Vw(U'ɘ', V::E),  Vw(U'ɤ', V::E),  Vw(U'ɚ', V::RR), Vw(U'ɝ', V::RR),
    Vw(U'i', V::I),  Vw(U'ɪ', V::I),  Vw(U'ɨ', V::I),  Vw(U'ɯ', V::I),  Vw(U'o', V::O),  Vw(U'ɔ', V::O),  Vw(U'ɒ', V::O),
    Vw(U'ø', V::O),  Vw(U'œ', V::O),  Vw(U'ɵ', V::O),  Vw(U'ɞ', V::O),  Vw(U'u', V::U),  Vw(U'ʊ', V::U),  Vw(U'y', V::U),
    Vw(U'ʏ', V::U),  Vw(U'ʉ', V::U),  {U'h', kTransparent, false},    {U'ɦ', kTransparent, false},    {U'ʔ', kTransparent, false},
    {U'ħ', kTransparent, false},      {U'ʕ', kTransparent, false},
};

const SymbolClass* findSymbol(char32_t c) {
  for (const SymbolClass& s : kSymbols)
    if (s.symbol == c) return &s;
  return nullptr;
}

// Unknown symbols by the Latin letter they are written on ("ẽ" -> e, "ʈ"
// is listed, "ǎ" -> a), so a new aligner's spelling lands in the nearest class.
const SymbolClass* classify(char32_t c) {
  if (const SymbolClass* s = findSymbol(c)) return s;
  const char base = latinBaseLetter(c);
  return base ? findSymbol(static_cast<char32_t>(base)) : nullptr;
}

// Affricates are one sound with the shape of their release.
struct Affricate {
  char32_t first, second;
  V viseme;
};
constexpr Affricate kAffricates[] = {{U't', U'ʃ', V::CH}, {U'd', U'ʒ', V::CH}, {U't', U'ɕ', V::CH}, {U'd', U'ʑ', V::CH},
                                     {U't', U's', V::SS}, {U'd', U'z', V::SS}, {U'p', U'f', V::FF}};

bool isJoiner(char32_t c) { return c == 0x200D || c == 0x0361 || c == 0x035C || c == 0x203F; }

// Marks that say how, not what: stress, length, tone letters and other
// modifier letters (U+02B0..U+02FF: ˈ ˌ ː ʰ ʷ ˥), combining diacritics
// (nasal ̃, dental ̪, ...), tone numbers, syllable breaks, joiners.
bool isMark(char32_t c) {
  return (c >= 0x02B0 && c <= 0x02FF) || (c >= 0x0300 && c <= 0x036F) || (c >= 0x1DC0 && c <= 0x1DFF) ||
         (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '\'' || c == 0x200C || isJoiner(c);
}

bool isSilenceLabel(std::string_view p) {
  for (std::string_view label : {"", "_", "sil", "SIL", "sp", "pau"})
    if (p == label) return true;
  return false;
}

bool isVowelSymbol(char32_t c) {
  const SymbolClass* s = classify(c);
  return s && s->vowel;
}

// espeak-ng's Vietnamese writes the sắc tone as "ɜ" after the nucleus
// ("t̪ˈoɜj" tối): a ɜ straight after another vowel is that tone, not a vowel.
bool isVietnameseToneMark(char32_t c, char32_t previousBase) { return c == U'ɜ' && isVowelSymbol(previousBase); }

}  // namespace

std::optional<PhonemeVisemes> visemesForIpa(std::string_view phoneme) {
  if (isSilenceLabel(phoneme)) return PhonemeVisemes{.kind = PhonemeVisemes::Kind::Silence};
  std::vector<char32_t> bases;
  for (size_t pos = 0; pos < phoneme.size();) {
    const char32_t c = nextCodepoint(phoneme, pos);
    if (isMark(c) || c == ' ') continue;
    if (!bases.empty() && isVietnameseToneMark(c, bases.back())) continue;
    bases.push_back(c);
  }
  PhonemeVisemes out;
  if (bases.size() == 2)
    for (const Affricate& a : kAffricates)
      if (bases[0] == a.first && bases[1] == a.second) return PhonemeVisemes{.visemes = {a.viseme}, .count = 1};
  bool transparent = false;
  std::vector<V> shapes;
  for (char32_t c : bases) {
    const SymbolClass* s = classify(c);
    if (!s) continue;
    if (s->viseme == kTransparent) {
      transparent = true;
      continue;
    }
    const V v = static_cast<V>(s->viseme);
    if (shapes.empty() || shapes.back() != v) shapes.push_back(v);
  }
  if (shapes.empty()) {
    if (!transparent) return std::nullopt;
    return PhonemeVisemes{.kind = PhonemeVisemes::Kind::Transparent};
  }
  // A diphthong (or a longer glide): where it starts and where it ends.
  out.visemes[0] = shapes.front();
  out.visemes[1] = shapes.back();
  out.count = shapes.size() > 1 ? 2 : 1;
  return out;
}

namespace {

// Symbol pairs that are one phoneme: the affricates and the diphthongs of
// English (aɪ aʊ eɪ oʊ əʊ ɔɪ ɪə eə ʊə), French has none, Vietnamese's
// centring ones (iə uə ɨə) and its əɪ, aɪ-like offglides.
bool joinsAsOnePhoneme(char32_t first, char32_t second) {
  for (const Affricate& a : kAffricates)
    if (a.first == first && a.second == second) return true;
  constexpr std::pair<char32_t, char32_t> kDiphthongs[] = {
      {U'a', U'ɪ'}, {U'a', U'ʊ'}, {U'e', U'ɪ'}, {U'o', U'ʊ'}, {U'ə', U'ʊ'}, {U'ɔ', U'ɪ'}, {U'ɪ', U'ə'},
      {U'e', U'ə'}, {U'ʊ', U'ə'}, {U'i', U'ə'}, {U'u', U'ə'}, {U'ɨ', U'ə'}, {U'ə', U'ɪ'}, {U'ɛ', U'ə'}};
  return std::find(std::begin(kDiphthongs), std::end(kDiphthongs), std::pair{first, second}) != std::end(kDiphthongs);
}

}  // namespace

std::vector<std::string> splitIpa(std::string_view text) {
  std::vector<std::string> phonemes;
  char32_t lastBase = 0;
  bool joinNext = false;
  for (size_t pos = 0; pos < text.size();) {
    const size_t start = pos;
    const char32_t c = nextCodepoint(text, pos);
    const std::string_view bytes = text.substr(start, pos - start);
    if (isMark(c)) {
      // Marks belong to the phoneme before them (length, tone, diacritics);
      // a stress mark before the first phoneme of a word is dropped.
      if (!phonemes.empty() && lastBase != 0) phonemes.back() += bytes;
      joinNext = joinNext || isJoiner(c);
      continue;
    }
    if (!classify(c)) {  // spaces, punctuation, anything unpronounced
      lastBase = 0;
      joinNext = false;
      continue;
    }
    const bool join = lastBase != 0 && (joinNext || joinsAsOnePhoneme(lastBase, c) || isVietnameseToneMark(c, lastBase));
    if (join)
      phonemes.back() += bytes;
    else
      phonemes.emplace_back(bytes);
    lastBase = c;
    joinNext = false;
  }
  return phonemes;
}

}  // namespace facial
