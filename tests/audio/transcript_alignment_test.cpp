#include "audio/transcript_alignment.h"

#include <gtest/gtest.h>

#include "tests/audio/speech_samples.h"

namespace {

constexpr double kWordTolerance = 0.1;  // seconds

// espeak-ng says when it spoke each word: the aligner, given only the sound and
// the text, must find nearly the same times.
void expectAlignsWithEspeak(const std::string& text) {
  auto speech = audio::synthesize(text);
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  auto alignment = audio::alignTranscript(audio_test::toFloat(speech->samples), speech->sampleRate, text);
  ASSERT_TRUE(alignment.ok()) << alignment.error().message;
  ASSERT_EQ(alignment->words.size(), speech->words.size());
  size_t close = 0;
  for (size_t i = 0; i < speech->words.size(); ++i) {
    const auto& aligned = alignment->words[i];
    const auto& spoken = speech->words[i];
    EXPECT_LT(aligned.start, aligned.end) << aligned.text;
    if (i > 0) {
      EXPECT_GE(aligned.start, alignment->words[i - 1].end - 1e-9) << aligned.text;
    }
    close += std::abs(aligned.start - spoken.start) < kWordTolerance && std::abs(aligned.end - spoken.end) < kWordTolerance;
  }
  EXPECT_GE(close, speech->words.size() * 8 / 10) << close << " of " << speech->words.size() << " words within "
                                                   << kWordTolerance << " s of espeak's times";
  for (const auto& phoneme : alignment->phonemes) {
    EXPECT_FALSE(phoneme.ipa.empty());
    EXPECT_LE(phoneme.start, phoneme.end);
    EXPECT_LE(phoneme.end, speech->durationSeconds());
  }
}

TEST(TranscriptAlignment, FindsEspeakWordTimesFromTheSoundAlone) {
  expectAlignsWithEspeak("Hello world, this is the news at nine tonight. Today, a big storm hit the coast.");
  expectAlignsWithEspeak("The quick brown fox jumps over the lazy dog.");
}

TEST(TranscriptAlignment, PhonemesAreTheDictionaryPronunciationInIpa) {
  auto speech = audio::synthesize("Hello world.");
  ASSERT_TRUE(speech.ok());
  auto alignment = audio::alignTranscript(audio_test::toFloat(speech->samples), speech->sampleRate, "Hello, WORLD!");
  ASSERT_TRUE(alignment.ok()) << alignment.error().message;
  std::vector<std::string> ipa;
  for (const auto& phoneme : alignment->phonemes) ipa.push_back(phoneme.ipa);
  // CMU dictionary: hello HH AH L OW, world W ER L D.
  EXPECT_EQ(ipa, (std::vector<std::string>{"h", "ə", "l", "oʊ", "w", "ɝ", "l", "d"}));
  ASSERT_EQ(alignment->words.size(), 2u);
  EXPECT_EQ(alignment->words[0].text, "hello");
  EXPECT_EQ(alignment->words[1].text, "world");
  EXPECT_DOUBLE_EQ(alignment->words[0].start, alignment->phonemes[0].start);
  EXPECT_DOUBLE_EQ(alignment->words[1].end, alignment->phonemes[7].end);
}

TEST(TranscriptAlignment, ArpabetToIpa) {
  EXPECT_EQ(audio::arpabetToIpa("AY"), "aɪ");
  EXPECT_EQ(audio::arpabetToIpa("AY1"), "aɪ");  // stress digits ignored
  EXPECT_EQ(audio::arpabetToIpa("TH"), "θ");
  EXPECT_EQ(audio::arpabetToIpa("ZH"), "ʒ");
  EXPECT_EQ(audio::arpabetToIpa("XX"), "");
}

TEST(TranscriptAlignment, RefusesWhatItCannotAlign) {
  const std::vector<float> tone = audio_test::tone(440, 1.0, 16000);
  auto unknown = audio::alignTranscript(tone, 16000, "hello zzqxvw");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().kind, eng::ErrorKind::NotFound);
  EXPECT_NE(unknown.error().message.find("'zzqxvw'"), std::string::npos) << unknown.error().message;
  auto number = audio::alignTranscript(tone, 16000, "at 9");
  ASSERT_FALSE(number.ok());
  EXPECT_NE(number.error().message.find("write numbers as words"), std::string::npos) << number.error().message;
  EXPECT_EQ(audio::alignTranscript(tone, 16000, " ,.; ").error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_FALSE(audio::alignTranscript({}, 16000, "hello").ok());
  EXPECT_FALSE(audio::alignTranscript(tone, 0, "hello").ok());
  auto tooLong = audio::alignTranscript(std::vector<float>(8000 * 601, 0.0f), 8000, "hello");
  ASSERT_FALSE(tooLong.ok());
  EXPECT_EQ(tooLong.error().kind, eng::ErrorKind::TooLarge);
}

}  // namespace
