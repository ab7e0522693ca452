#include "facial/runtime/speech/ipa_visemes.h"

#include <algorithm>
#include <string_view>

#include "facial/runtime/speech/utf8_text.h"

namespace facial {
namespace {

using V = Viseme;

// What a base symbol is: a viseme, or no shape of its own.
struct SymbolClass {
  int8_t viseme;  // a Viseme, or kTransparent
  bool vowel;     // a syllable nucleus (diphthongs join vowels; j, w, ɥ are glides, not vowels)
};
constexpr int8_t kTransparent = -1;

struct SymbolGroup {
  SymbolClass cls;
  std::u32string_view symbols;
};
constexpr SymbolClass C(V v) { return {static_cast<int8_t>(v), false}; }
constexpr SymbolClass Vowel(V v) { return {static_cast<int8_t>(v), true}; }

// The consonants and vowels of English, French and Vietnamese (and their IPA
// neighbours) in the Oculus classes: PP bilabials, FF labiodentals, TH
// dentals, DD alveolar stops and taps, nn nasals and laterals (Oculus puts l
// with n), kk velars, uvular stops and palatal stops, CH postalveolars, SS
// sibilants, RR rhotics; the glides j (I) and w, ɥ (U). Vowels by their
// visible shape: aa open, E mid unrounded (and schwa), I close unrounded, O
// mid/open rounded, U close rounded (the French front rounded y rounds like u,
// ø and œ like o). h and the glottals have no shape of their own.
constexpr SymbolGroup kSymbolGroups[] = {
    {C(V::PP), U"pbmɓʙ"},      {C(V::FF), U"fvɸβʋɱ"},     {C(V::TH), U"θð"},
    {C(V::DD), U"tdɗʈɖɾɽɬɮ"},  {C(V::nn), U"nɲŋɳɴlɫɭʎʟ"}, {C(V::kk), U"kgɡxɣqɢχɠcɟ"},
    {C(V::CH), U"ʃʒɕʑʂʐçʝ"},   {C(V::SS), U"sz"},         {C(V::RR), U"rɹɻʁʀ"},
    {C(V::I), U"j"},           {C(V::U), U"wɥʍ"},         {Vowel(V::aa), U"aɑɐæʌäɶ"},
    {Vowel(V::E), U"eɛəɜɘɤ"},  {Vowel(V::RR), U"ɚɝ"},     {Vowel(V::I), U"iɪɨɯ"},
    {Vowel(V::O), U"oɔɒøœɵɞ"}, {Vowel(V::U), U"uʊyʏʉ"},   {{kTransparent, false}, U"hɦʔħʕ"},
};

const SymbolClass* findSymbol(char32_t c) {
  for (const SymbolGroup& g : kSymbolGroups)
    if (g.symbols.find(c) != std::u32string_view::npos) return &g.cls;
  return nullptr;
}

// Unknown symbols by the Latin letter they are written on ("ẽ" -> e, "ǎ" ->
// a), so a new aligner's spelling lands in the nearest class.
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
    const bool join =
        lastBase != 0 && (joinNext || joinsAsOnePhoneme(lastBase, c) || isVietnameseToneMark(c, lastBase));
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
