#include "audio/syllable_envelope.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>

#include "audio/audio_file.h"
#include "audio/speech_synthesis.h"
#include "tests/audio/speech_samples.h"
#include "tests/common/test_support.h"

namespace {

using audio::MouthState;

// IPA vowels (the first letter of espeak's vowel phonemes, diphthongs included).
bool isVowel(const std::string& ipa) {
  static const std::vector<std::string> vowels = {"a", "e", "i", "o", "u", "y", "æ", "ɑ", "ɒ", "ɐ", "ə", "ɚ", "ɛ", "ɜ",
                                                  "ɪ", "ʊ", "ʌ", "ɔ", "ø", "œ", "ɤ", "ɯ", "ɨ", "ʏ", "ɵ"};
  return std::any_of(vowels.begin(), vowels.end(), [&](const std::string& v) { return ipa.rfind(v, 0) == 0; });
}

bool overlaps(double aStart, double aEnd, double bStart, double bEnd, double tolerance) {
  return aStart < bEnd + tolerance && bStart < aEnd + tolerance;
}

MouthState stateAt(const audio::SyllableEnvelope& envelope, double t) {
  for (const auto& segment : envelope.segments)
    if (t >= segment.start && t < segment.end) return segment.state;
  return MouthState::Rest;
}

void expectContiguous(const audio::SyllableEnvelope& envelope, double duration) {
  ASSERT_FALSE(envelope.segments.empty());
  EXPECT_DOUBLE_EQ(envelope.segments.front().start, 0.0);
  EXPECT_DOUBLE_EQ(envelope.segments.back().end, duration);
  for (size_t i = 1; i < envelope.segments.size(); ++i) {
    EXPECT_DOUBLE_EQ(envelope.segments[i].start, envelope.segments[i - 1].end);
    EXPECT_LT(envelope.segments[i].start, envelope.segments[i].end);
  }
  EXPECT_EQ(envelope.mouthOpen.size(), size_t(std::ceil(duration * envelope.framesPerSecond)));
}

constexpr double kAlignTolerance = 0.03;  // 30 ms, a frame at 30 fps

TEST(SyllableEnvelope, OpensOnEspeakVowelsAndRestsInPauses) {
  auto speech = audio::synthesize("Hello world, this is the news at nine tonight. Today, a big storm hit the coast.");
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  auto envelope = audio::syllableEnvelope(audio_test::toFloat(speech->samples), speech->sampleRate, 30);
  ASSERT_TRUE(envelope.ok()) << envelope.error().message;
  expectContiguous(*envelope, speech->durationSeconds());

  std::vector<audio::TimedPhoneme> vowels;
  std::copy_if(speech->phonemes.begin(), speech->phonemes.end(), std::back_inserter(vowels), [](const auto& p) { return isVowel(p.ipa); });
  ASSERT_GE(vowels.size(), 15u);
  std::vector<audio::MouthSegment> open;
  std::copy_if(envelope->segments.begin(), envelope->segments.end(), std::back_inserter(open),
               [](const auto& s) { return s.state == MouthState::Open; });
  size_t vowelsOpened = 0, opensOnVowels = 0;
  for (const auto& vowel : vowels)
    vowelsOpened += std::any_of(open.begin(), open.end(),
                                [&](const auto& s) { return overlaps(vowel.start, vowel.end, s.start, s.end, kAlignTolerance); });
  for (const auto& segment : open)
    opensOnVowels += std::any_of(vowels.begin(), vowels.end(),
                                 [&](const auto& v) { return overlaps(v.start, v.end, segment.start, segment.end, kAlignTolerance); });
  EXPECT_GE(vowelsOpened, vowels.size() * 9 / 10) << vowelsOpened << " of " << vowels.size() << " vowels opened the mouth";
  EXPECT_GE(opensOnVowels, open.size() * 9 / 10) << opensOnVowels << " of " << open.size() << " openings on a vowel";
  EXPECT_NEAR(double(envelope->nuclei.size()), double(vowels.size()), 0.2 * vowels.size());

  // espeak's pauses (the gaps between its phonemes: the commas and the full stop) are rest.
  size_t pauses = 0;
  for (size_t i = 1; i < speech->phonemes.size(); ++i) {
    const double gapStart = speech->phonemes[i - 1].end, gapEnd = speech->phonemes[i].start;
    if (gapEnd - gapStart < 0.15) continue;
    ++pauses;
    EXPECT_EQ(stateAt(*envelope, (gapStart + gapEnd) / 2), MouthState::Rest) << "pause at " << gapStart;
    EXPECT_EQ(envelope->mouthOpen[size_t((gapStart + gapEnd) / 2 * 30)], 0.0f);
  }
  EXPECT_GE(pauses, 2u);
}

TEST(SyllableEnvelope, MouthCurvePeaksOnNucleiAndIsZeroAtRest) {
  auto speech = audio::synthesize("Bonjour à tous, voici les nouvelles.", {.language = "fr"});
  ASSERT_TRUE(speech.ok()) << speech.error().message;
  auto envelope = audio::syllableEnvelope(audio_test::toFloat(speech->samples), speech->sampleRate, 60);
  ASSERT_TRUE(envelope.ok()) << envelope.error().message;
  expectContiguous(*envelope, speech->durationSeconds());
  for (double nucleus : envelope->nuclei) {
    EXPECT_EQ(stateAt(*envelope, nucleus), MouthState::Open) << nucleus;
    EXPECT_GT(envelope->mouthOpen[std::min(envelope->mouthOpen.size() - 1, size_t(nucleus * 60))], 0.3f) << nucleus;
  }
  for (size_t i = 0; i < envelope->mouthOpen.size(); ++i) {
    EXPECT_GE(envelope->mouthOpen[i], 0.0f);
    EXPECT_LE(envelope->mouthOpen[i], 1.0f);
    if (stateAt(*envelope, i / 60.0) == MouthState::Rest) {
      EXPECT_EQ(envelope->mouthOpen[i], 0.0f) << i;
    }
  }
}

TEST(SyllableEnvelope, SilenceIsOneRest) {
  for (float level : {0.0f, 1e-5f}) {  // digital silence, and a hiss far below speech
    std::vector<float> quiet = audio_test::tone(1000, 1.5, 16000, level);
    auto envelope = audio::syllableEnvelope(quiet, 16000, 25);
    ASSERT_TRUE(envelope.ok()) << envelope.error().message;
    ASSERT_EQ(envelope->segments.size(), 1u) << level;
    EXPECT_EQ(envelope->segments[0].state, MouthState::Rest);
    EXPECT_TRUE(envelope->nuclei.empty());
    EXPECT_TRUE(std::all_of(envelope->mouthOpen.begin(), envelope->mouthOpen.end(), [](float v) { return v == 0.0f; }));
  }
}

TEST(SyllableEnvelope, SpeechBetweenSilencesStartsAndEndsAtRest) {
  auto speech = audio::synthesize("One, two.");
  ASSERT_TRUE(speech.ok());
  std::vector<float> padded(speech->sampleRate / 2, 0.0f);
  const std::vector<float> voice = audio_test::toFloat(speech->samples);
  padded.insert(padded.end(), voice.begin(), voice.end());
  padded.resize(padded.size() + speech->sampleRate / 2, 0.0f);
  auto envelope = audio::syllableEnvelope(padded, speech->sampleRate, 30);
  ASSERT_TRUE(envelope.ok());
  expectContiguous(*envelope, double(padded.size()) / speech->sampleRate);
  EXPECT_EQ(envelope->segments.front().state, MouthState::Rest);
  EXPECT_GE(envelope->segments.front().end, 0.45);
  EXPECT_EQ(envelope->segments.back().state, MouthState::Rest);
  EXPECT_GE(envelope->segments.back().end - envelope->segments.back().start, 0.45);
  EXPECT_EQ(envelope->nuclei.size(), 2u);  // "one", "two"
}

TEST(SyllableEnvelope, RefusesBadArgumentsAndSurvivesNonFiniteSamples) {
  std::vector<float> samples(1600, 0.1f);
  EXPECT_FALSE(audio::syllableEnvelope({}, 16000, 30).ok());
  EXPECT_FALSE(audio::syllableEnvelope(samples, 0, 30).ok());
  EXPECT_FALSE(audio::syllableEnvelope(samples, 16000, 0).ok());
  EXPECT_FALSE(audio::syllableEnvelope(samples, 16000, NAN).ok());
  samples[10] = NAN;
  samples[20] = INFINITY;
  auto envelope = audio::syllableEnvelope(samples, 16000, 30);
  ASSERT_TRUE(envelope.ok());
  for (float v : envelope->mouthOpen) EXPECT_TRUE(std::isfinite(v));
}

// The French recordings alone: where Rhubarb Lip Sync (the JSON beside each,
// made by another tool) rests the mouth (X) for a while, ours is not open;
// where Rhubarb opens it (C, D, E: open and half-open vowels), ours is not at rest.
TEST(SyllableEnvelope, SharedRecordingsAgreeWithRhubarbOnRestAndOpen) {
  FACIAL_REQUIRE_SHARED();
  const auto dir = testing_support::sharedDir() / "speech";
  for (const char* name : {"bonjour", "youpi"}) {
    const auto sound = dir / (std::string(name) + ".ogg"), cuesFile = dir / (std::string(name) + ".json");
    if (!std::filesystem::exists(sound) || !std::filesystem::exists(cuesFile)) GTEST_SKIP() << sound << " or its cues are absent";
    auto clip = audio::readAudioFile(sound);
    ASSERT_TRUE(clip.ok()) << clip.error().message;
    auto envelope = audio::syllableEnvelope(clip->samples, clip->sampleRate, 30);
    ASSERT_TRUE(envelope.ok());
    const nlohmann::json cues = nlohmann::json::parse(std::ifstream(cuesFile))["mouthCues"];
    size_t restCues = 0, restAgreed = 0, openCues = 0, openAgreed = 0;
    for (const auto& cue : cues) {
      const double start = cue["start"], end = cue["end"], middle = (start + end) / 2;
      const std::string shape = cue["value"];
      if (shape == "X" && end - start >= 0.15) {
        ++restCues;
        restAgreed += stateAt(*envelope, middle) != MouthState::Open;
      } else if (shape == "C" || shape == "D" || shape == "E") {
        ++openCues;
        openAgreed += stateAt(*envelope, middle) != MouthState::Rest;
      }
    }
    ASSERT_GT(restCues, 0u) << name;
    ASSERT_GT(openCues, 0u) << name;
    EXPECT_GE(restAgreed, restCues * 8 / 10) << name << ": " << restAgreed << " of " << restCues << " rests";
    EXPECT_GE(openAgreed, openCues * 8 / 10) << name << ": " << openAgreed << " of " << openCues << " openings";
  }
}

}  // namespace
