#include "audio/speech_synthesis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>

namespace {

std::vector<std::string> wordTexts(const audio::Speech& speech) {
  std::vector<std::string> texts;
  for (const auto& word : speech.words) texts.push_back(word.text);
  return texts;
}

// Phonemes and words are in order, inside the audio, and each word spans phonemes.
void expectConsistentTiming(const audio::Speech& speech) {
  ASSERT_FALSE(speech.phonemes.empty());
  double previousEnd = 0;
  for (const auto& phoneme : speech.phonemes) {
    EXPECT_FALSE(phoneme.ipa.empty());
    EXPECT_GE(phoneme.start, previousEnd - 1e-9) << phoneme.ipa;
    EXPECT_GE(phoneme.end, phoneme.start) << phoneme.ipa;  // espeak gives some zero-length ones
    EXPECT_LE(phoneme.end, speech.durationSeconds() + 1e-9) << phoneme.ipa;
    previousEnd = phoneme.end;
  }
  for (size_t i = 0; i < speech.words.size(); ++i) {
    EXPECT_LT(speech.words[i].start, speech.words[i].end) << speech.words[i].text;
    if (i > 0) {
      EXPECT_GE(speech.words[i].start, speech.words[i - 1].end - 1e-9) << speech.words[i].text;
    }
  }
}

TEST(SpeechSynthesis, EnglishHasAudioIpaPhonemesAndWords) {
  auto speech = audio::synthesize("Hello world, this is the news.");
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  EXPECT_EQ(speech->sampleRate, 22050);
  EXPECT_GT(speech->durationSeconds(), 1.0);
  EXPECT_LT(speech->durationSeconds(), 5.0);
  const auto loudest = std::max_element(speech->samples.begin(), speech->samples.end(),
                                        [](int16_t a, int16_t b) { return std::abs(a) < std::abs(b); });
  EXPECT_GT(std::abs(*loudest), 3000);  // speech, not silence
  EXPECT_EQ(wordTexts(*speech), (std::vector<std::string>{"Hello", "world", "this", "is", "the", "news"}));
  expectConsistentTiming(*speech);
  // IPA names, not espeak's own mnemonics: "world" has the vowel ɜː, "this" starts with ð.
  auto has = [&](const char* ipa) {
    return std::any_of(speech->phonemes.begin(), speech->phonemes.end(), [&](const auto& p) { return p.ipa == ipa; });
  };
  EXPECT_TRUE(has("ɜː"));
  EXPECT_TRUE(has("ð"));
  EXPECT_TRUE(has("h"));
}

TEST(SpeechSynthesis, VietnameseWordsKeepTheirLetters) {
  auto speech = audio::synthesize("Xin chào, đây là bản tin tối nay.", {.language = "vi"});
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  EXPECT_EQ(wordTexts(*speech), (std::vector<std::string>{"Xin", "chào", "đây", "là", "bản", "tin", "tối", "nay"}));
  expectConsistentTiming(*speech);
}

TEST(SpeechSynthesis, FrenchSpeaks) {
  auto speech = audio::synthesize("Bonjour, je suis très content.", {.language = "fr"});
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  EXPECT_EQ(wordTexts(*speech).front(), "Bonjour");
  expectConsistentTiming(*speech);
  // French nasal vowel of "bonjour" in IPA.
  EXPECT_TRUE(std::any_of(speech->phonemes.begin(), speech->phonemes.end(), [](const auto& p) { return p.ipa == "ɔ̃"; }));
}

TEST(SpeechSynthesis, RateChangesTheDuration) {
  auto normal = audio::synthesize("The quick brown fox jumps over the lazy dog.");
  auto fast = audio::synthesize("The quick brown fox jumps over the lazy dog.", {.ratePercent = 200});
  auto slow = audio::synthesize("The quick brown fox jumps over the lazy dog.", {.ratePercent = 60});
  ASSERT_TRUE(normal.ok() && fast.ok() && slow.ok());
  EXPECT_LT(fast->durationSeconds(), normal->durationSeconds() * 0.75);
  EXPECT_GT(slow->durationSeconds(), normal->durationSeconds() * 1.3);
}

TEST(SpeechSynthesis, PitchChangesTheSound) {
  auto low = audio::synthesize("Hello there.", {.pitchPercent = 40});
  auto high = audio::synthesize("Hello there.", {.pitchPercent = 180});
  ASSERT_TRUE(low.ok() && high.ok());
  EXPECT_NE(low->samples, high->samples);
}

TEST(SpeechSynthesis, UnknownLanguageNamesItAndListsKnownOnes) {
  auto speech = audio::synthesize("Hello", {.language = "klingon-xx"});
  ASSERT_FALSE(speech.ok());
  EXPECT_EQ(speech.error().kind, eng::ErrorKind::NotFound);
  const std::string& message = speech.error().message;
  EXPECT_NE(message.find("'klingon-xx'"), std::string::npos) << message;
  EXPECT_NE(message.find("en"), std::string::npos) << message;
  EXPECT_NE(message.find("vi"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // The synthesiser still works after a refused voice.
  EXPECT_TRUE(audio::synthesize("Hello").ok());
}

TEST(SpeechSynthesis, RefusesEmptyHugeAndOutOfRangeRequests) {
  auto empty = audio::synthesize("");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_FALSE(audio::synthesize(" \n\t ").ok());
  auto huge = audio::synthesize(std::string(audio::kMaxSpeechCharacters + 1, 'a'));
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_NE(huge.error().message.find(std::to_string(audio::kMaxSpeechCharacters)), std::string::npos) << huge.error().message;
  EXPECT_FALSE(audio::synthesize("Hi", {.ratePercent = 10}).ok());
  EXPECT_FALSE(audio::synthesize("Hi", {.ratePercent = NAN}).ok());
  EXPECT_FALSE(audio::synthesize("Hi", {.pitchPercent = 500}).ok());
  EXPECT_FALSE(audio::synthesize("Hi", {.language = ""}).ok());
}

TEST(SpeechSynthesis, LimitCountsCharactersNotBytes) {
  std::string text;
  for (size_t i = 0; i <= audio::kMaxSpeechCharacters; ++i) text += "é";  // two bytes each
  auto speech = audio::synthesize(text, {.language = "fr"});
  ASSERT_FALSE(speech.ok());
  const std::string counted = "has " + std::to_string(audio::kMaxSpeechCharacters + 1);
  EXPECT_NE(speech.error().message.find(counted), std::string::npos) << speech.error().message;
}

std::vector<std::string> ipaSequence(const audio::Speech& speech) {
  std::vector<std::string> ipa;
  for (const auto& phoneme : speech.phonemes) ipa.push_back(phoneme.ipa);
  return ipa;
}

// espeak-ng's samples vary a little from call to call (its noise sources),
// its phonemes and words do not: concurrent calls, serialised by the mutex,
// each get the whole, uncorrupted utterance.
TEST(SpeechSynthesis, ConcurrentCallsEachGetTheWholeUtterance) {
  auto expected = audio::synthesize("One two three.");
  ASSERT_TRUE(expected.ok());
  std::vector<std::optional<audio::Speech>> results(4);
  std::vector<std::thread> threads;
  for (size_t i = 0; i < results.size(); ++i)
    threads.emplace_back([&, i] {
      auto speech = audio::synthesize("One two three.");
      if (speech.ok()) results[i] = std::move(speech).value();
    });
  for (auto& thread : threads) thread.join();
  for (const auto& result : results) {
    ASSERT_TRUE(result.has_value());
    EXPECT_EQ(ipaSequence(*result), ipaSequence(*expected));
    EXPECT_EQ(wordTexts(*result), wordTexts(*expected));
    EXPECT_NEAR(result->durationSeconds(), expected->durationSeconds(), 0.1 * expected->durationSeconds());
  }
}

TEST(SpeechSynthesis, ListsItsLanguages) {
  auto languages = audio::speechLanguages();
  ASSERT_TRUE(languages.ok()) << languages.error().message;
  for (const char* wanted : {"en", "fr", "vi"})
    EXPECT_TRUE(std::binary_search(languages->begin(), languages->end(), std::string(wanted))) << wanted;
}

}  // namespace
