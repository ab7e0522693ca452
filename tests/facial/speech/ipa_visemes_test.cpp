// IPA -> visemes on real espeak-ng transcriptions (espeak-ng 1.51, `-q --ipa`)
// of English, French and Vietnamese, and the symbol handling under them.
#include "facial/runtime/speech/ipa_visemes.h"

#include <gtest/gtest.h>

#include <string>

using namespace facial;

namespace {

// "SS I nn": each phoneme's visemes, a diphthong as "E+I", h as "-", an unmappable one as "?".
std::string visemesOf(std::string_view transcription) {
  std::string out;
  for (const std::string& phoneme : splitIpa(transcription)) {
    const auto mapped = visemesForIpa(phoneme);
    std::string word = !mapped                                             ? "?"
                       : mapped->kind == PhonemeVisemes::Kind::Transparent ? "-"
                       : mapped->kind == PhonemeVisemes::Kind::Silence     ? "sil"
                                                                       : std::string(visemeName(mapped->visemes[0]));
    if (mapped && mapped->count == 2) word += "+" + std::string(visemeName(mapped->visemes[1]));
    out += (out.empty() ? "" : " ") + word;
  }
  return out;
}

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "|") + p;
  return out;
}

}  // namespace

TEST(IpaVisemes, English) {
  // "Good evening. Here is the news."
  EXPECT_EQ(visemesOf("ɡˈʊd ˈiːvnɪŋ"), "kk U DD I FF nn I nn");
  EXPECT_EQ(visemesOf("hˈiəɹ ɪz ðə njˈuːz"), "- I+E RR I SS TH E nn I U SS");
  // church judge thing measure boy cow: affricates, th, diphthongs
  EXPECT_EQ(visemesOf("tʃˈɜːtʃ dʒˈʌdʒ θˈɪŋ mˈɛʒə bˈɔɪ kˈaʊ"), "CH E CH CH aa CH TH I nn PP E CH E PP O+I kk aa+U");
}

TEST(IpaVisemes, French) {
  // "Bonjour", "Un bon vin blanc": nasal vowels by their oral vowel, uvular r as RR
  EXPECT_EQ(visemesOf("bɔ̃ʒˈuʁ"), "PP O CH U RR");
  EXPECT_EQ(visemesOf("œ̃ bˈɔ̃ vˈɛ̃ blˈɑ̃"), "O PP O FF E PP nn aa");
  // "voici les nouvelles du soir": the front rounded y rounds
  EXPECT_EQ(visemesOf("vwasˌi le- nuvˈɛl dy- swˈaʁ"), "FF U aa SS I nn E nn U FF E nn DD U SS U aa RR");
}

TEST(IpaVisemes, Vietnamese) {
  // "Xin chào, đây là bản tin tối nay.": tone numbers stripped, ɗ and dental t̪ as DD,
  // the sắc tone written "ɜ" after a vowel ("t̪ˈoɜj" tối) is a tone, not a vowel.
  EXPECT_EQ(visemesOf("sˈi1n tʃˈaː2w"), "SS I nn CH aa U");
  EXPECT_EQ(visemesOf("ɗˈəɪ1 lˌaː2 bˈaː4n t̪ˈi1n t̪ˈoɜj nˈa7j"), "DD E+I nn aa PP aa nn DD I nn DD O I nn aa I");
  EXPECT_EQ(joined(splitIpa("t̪ˈoɜj")), "t̪ˈ|oɜ|j");
  // "Người Việt": the centring diphthongs iə, ɨə (espeak-ng --ipa=3 ties them with U+200D)
  EXPECT_EQ(visemesOf("ŋˈy‍ə2j vˈi‍ɛ6t̪"), "nn U+E I FF I+E DD");
}

TEST(IpaVisemes, MarksAreStripped) {
  EXPECT_EQ(visemesForIpa("ˈaː")->visemes[0], Viseme::aa);
  EXPECT_EQ(visemesForIpa("ɔ̃")->visemes[0], Viseme::O);
  EXPECT_EQ(visemesForIpa("t̪")->visemes[0], Viseme::DD);
  EXPECT_EQ(visemesForIpa("a˧˥")->visemes[0], Viseme::aa);  // Chao tone letters
  EXPECT_EQ(visemesForIpa("kʷ")->visemes[0], Viseme::kk);
  EXPECT_EQ(visemesForIpa("t͡ʃ")->visemes[0], Viseme::CH);
  EXPECT_EQ(visemesForIpa("t͡ʃ")->count, 1);
}

TEST(IpaVisemes, DiphthongsGiveTheirStartAndEnd) {
  const auto ai = visemesForIpa("aɪ");
  ASSERT_TRUE(ai);
  EXPECT_EQ(ai->count, 2);
  EXPECT_EQ(ai->visemes[0], Viseme::aa);
  EXPECT_EQ(ai->visemes[1], Viseme::I);
  EXPECT_EQ(visemesForIpa("eɪ")->count, 2);  // E -> I
  EXPECT_EQ(visemesForIpa("ɛː")->count, 1);  // a long vowel is not a diphthong
}

TEST(IpaVisemes, SilenceAndShapelessPhonemes) {
  for (const char* pause : {"", "_", "sil", "sp", "pau"})
    EXPECT_EQ(visemesForIpa(pause)->kind, PhonemeVisemes::Kind::Silence) << pause;
  for (const char* shapeless : {"h", "ʔ", "ɦ"})
    EXPECT_EQ(visemesForIpa(shapeless)->kind, PhonemeVisemes::Kind::Transparent) << shapeless;
}

TEST(IpaVisemes, UnknownSymbolsFallBackToTheirBaseLetterOrAreReported) {
  EXPECT_EQ(visemesForIpa("ẽ")->visemes[0], Viseme::E);  // precomposed, not in the table
  EXPECT_EQ(visemesForIpa("ǎ")->visemes[0], Viseme::aa);
  EXPECT_EQ(visemesForIpa("Ø")->visemes[0], Viseme::O);
  EXPECT_FALSE(visemesForIpa("☃"));
  EXPECT_FALSE(visemesForIpa("#"));
  EXPECT_FALSE(visemesForIpa("\xff\xfe"));  // broken UTF-8 is unmappable, not a crash
}
