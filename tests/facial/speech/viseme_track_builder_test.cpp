// The coarticulation rules of VisemeTrackBuilder, one result test per rule
// (speech_rules in viseme_track.h), then the builder's input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "facial/runtime/speech/ipa_visemes.h"
#include "tests/facial/speech/speech_test_support.h"

using namespace facial;
using namespace facial::speech_test;
using namespace facial::speech_rules;

// --- Rule: vowel anticipation -------------------------------------------------

TEST(VisemeTrackRules, VowelShapeStartsBeforeItsOnset) {
  // "sa": s 0-0.2, a from 0.2.
  const VisemeTrack track = buildOrDie(phonemeRun({{"s", 0.2f}, {"a", 0.3f}}));
  EXPECT_GT(sampleAt(track, 0.2f - 0.08f)[Viseme::aa], 0.15f) << "80 ms before the vowel its shape is forming";
  EXPECT_LT(sampleAt(track, 0.0f)[Viseme::aa], 0.05f) << "200 ms before, it has not started";
  EXPECT_GT(sampleAt(track, 0.1f)[Viseme::SS], 0.5f) << "the consonant still leads in its own middle";
}

TEST(VisemeTrackRules, RoundingSpreadsAcrossPrecedingConsonants) {
  // "astu" against "asti": the s is already rounded before u, not before i.
  const VisemeTrack rounded = buildOrDie(phonemeRun({{"a", 0.2f}, {"s", 0.1f}, {"t", 0.06f}, {"u", 0.25f}}));
  const VisemeTrack spread = buildOrDie(phonemeRun({{"a", 0.2f}, {"s", 0.1f}, {"t", 0.06f}, {"i", 0.25f}}));
  const float sMiddle = 0.25f;
  EXPECT_GT(sampleAt(rounded, sMiddle)[Viseme::U], 0.2f);
  EXPECT_GT(sampleAt(rounded, sMiddle)[Viseme::U], 2.0f * sampleAt(spread, sMiddle)[Viseme::I]);
  EXPECT_GT(sampleAt(rounded, sMiddle)[MouthChannel::LipRounding], 0.2f);
}

// --- Rule: bilabial closure --------------------------------------------------

TEST(VisemeTrackRules, BilabialsCloseTheLipsFully) {
  const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.2f}, {"m", 0.08f}, {"a", 0.2f}}));
  for (float t = 0.2f; t <= 0.28f; t += 0.005f) {
    const Frame f = sampleAt(track, t);
    EXPECT_GT(f[Viseme::PP], 0.99f) << "t = " << t;
    EXPECT_GT(f[MouthChannel::LipClosure], 0.99f) << "t = " << t;
    EXPECT_LT(f[MouthChannel::JawOpen], 0.01f) << "t = " << t;
  }
}

TEST(VisemeTrackRules, AShortVowelBetweenBilabialsStillOpensTheMouth) {
  // "mama" as espeak-ng times it: the 52 ms vowel between two m's opens the
  // jaw, each m closes fully (the m's dominance and closure ramps once kept
  // the whole word shut).
  const VisemeTrack track = buildOrDie(phonemeRun({{"m", 0.081f}, {"a", 0.052f}, {"m", 0.064f}, {"a", 0.051f}}, 0.5f));
  const float firstVowelMiddle = 0.5f + 0.081f + 0.026f, secondM = 0.5f + 0.133f + 0.032f;
  EXPECT_GT(sampleAt(track, firstVowelMiddle)[Viseme::aa], 0.6f);
  EXPECT_GT(sampleAt(track, firstVowelMiddle)[MouthChannel::JawOpen], 0.6f);
  EXPECT_LT(sampleAt(track, firstVowelMiddle)[MouthChannel::LipClosure], 0.4f);
  EXPECT_GT(sampleAt(track, secondM)[MouthChannel::LipClosure], 0.99f);
}

TEST(VisemeTrackRules, AVeryShortBilabialStillClosesForTheMinimumHold) {
  // A 15 ms b between open vowels: closed for 40 ms (kMinClosureHold) around its centre.
  const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.2f}, {"b", 0.015f}, {"a", 0.2f}}));
  const float centre = 0.2075f;
  for (float t = centre - 0.019f; t < centre + 0.02f; t += 0.002f) {
    EXPECT_GT(sampleAt(track, t)[Viseme::PP], 0.99f) << "t = " << t;
    EXPECT_GT(sampleAt(track, t)[MouthChannel::LipClosure], 0.99f) << "t = " << t;
  }
}

TEST(VisemeTrackRules, FromRestABilabialKeepsTheLipsClosed) {
  // "(pause) b ɔ̃": no jaw opening between rest and the b for the anticipated vowel.
  const VisemeTrack track = buildOrDie(phonemeRun({{"b", 0.07f}, {"ɔ̃", 0.12f}}, 0.5f));
  for (float t = 0.5f - 0.1f; t < 0.57f; t += 0.005f) {  // the 100 ms before the b, and the b
    EXPECT_LT(sampleAt(track, t)[MouthChannel::JawOpen], 0.01f) << "t = " << t;
    EXPECT_GT(sampleAt(track, t)[MouthChannel::LipClosure], 0.99f) << "t = " << t;
  }
}

// --- Rule: labiodentals ------------------------------------------------------

TEST(VisemeTrackRules, LabiodentalIsTheDominantShapeOfItsInterval) {
  const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.2f}, {"f", 0.06f}, {"a", 0.2f}}));
  const Frame f = sampleAt(track, 0.23f);
  EXPECT_GT(f[Viseme::FF], 0.5f);
  for (size_t v = 0; v < kVisemeCount; ++v) {
    if (static_cast<Viseme>(v) == Viseme::FF) continue;
    EXPECT_LT(f.visemes[v], f[Viseme::FF]) << visemeName(static_cast<Viseme>(v));
  }
}

// --- Rule: rounded vowels ----------------------------------------------------

TEST(VisemeTrackRules, RoundedVowelsRoundTheLips) {
  const VisemeTrack track =
      buildOrDie(phonemeRun({{"t", 0.08f}, {"u", 0.2f}, {"d", 0.08f}, {"o", 0.2f}, {"d", 0.08f}, {"i", 0.2f}}));
  const Frame u = sampleAt(track, 0.18f), o = sampleAt(track, 0.46f), i = sampleAt(track, 0.74f);
  EXPECT_GT(u[Viseme::U], 0.7f);
  EXPECT_GT(o[Viseme::O], 0.7f);
  EXPECT_GT(u[MouthChannel::LipRounding], 0.7f);
  EXPECT_GT(o[MouthChannel::LipRounding], 0.5f);
  EXPECT_LT(i[MouthChannel::LipRounding], 0.1f);
}

// --- Rule: short phonemes are never dropped ----------------------------------

TEST(VisemeTrackRules, ATwentyMillisecondConsonantReachesAVisiblePeak) {
  for (const char* consonant : {"t", "k", "s", "n", "ʃ"}) {
    const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.2f}, {consonant, 0.02f}, {"a", 0.2f}}));
    const Viseme v = visemesForIpa(consonant)->visemes[0];
    EXPECT_GT(peakOver(track, v, 0.19f, 0.23f), 0.5f) << consonant;  // visible: at least half the shape
  }
}

// --- Rule: pauses ------------------------------------------------------------

TEST(VisemeTrackRules, ALongPauseRelaxesToRest) {
  std::vector<TimedPhoneme> p = phonemeRun({{"a", 0.3f}});
  p.push_back({"a", 0.7f, 1.0f});  // 400 ms of silence between
  const VisemeTrack track = buildOrDie(p);
  const Frame middle = sampleAt(track, 0.5f);
  EXPECT_GT(middle[Viseme::sil], 0.9f);
  EXPECT_LT(middle[MouthChannel::JawOpen], 0.1f);
}

TEST(VisemeTrackRules, AShortGapIsBridged) {
  std::vector<TimedPhoneme> p = phonemeRun({{"a", 0.3f}});
  p.push_back({"a", 0.36f, 0.6f});  // 60 ms gap: the mouth keeps talking
  const VisemeTrack track = buildOrDie(p);
  EXPECT_LT(sampleAt(track, 0.33f)[Viseme::sil], 0.2f);
  EXPECT_GT(sampleAt(track, 0.33f)[MouthChannel::JawOpen], 0.6f);
}

TEST(VisemeTrackRules, TheTrackStartsAndEndsAtRest) {
  const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.3f}}, 1.0f));
  EXPECT_FLOAT_EQ(sampleAt(track, track.startTime() - 1.0f)[Viseme::sil], 1.0f);
  EXPECT_FLOAT_EQ(sampleAt(track, track.endTime() + 1.0f)[Viseme::sil], 1.0f);
  EXPECT_GT(sampleAt(track, 0.5f)[Viseme::sil], 0.99f);
}

// --- Rules over a whole utterance: no pops, bounds, dominance blending -------

std::vector<TimedPhoneme> randomUtterance(uint32_t seed) {
  const char* inventory[] = {"p", "b", "m", "f", "v", "θ", "t",  "d",  "k", "ɡ", "tʃ", "s", "z", "n", "l", "ɹ",
                             "h", "a", "ɛ", "i", "ɔ", "u", "aɪ", "oʊ", "ə", "ʁ", "y",  "ɔ̃", "ŋ", "ɗ", "_"};
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, std::size(inventory) - 1);
  std::uniform_real_distribution<float> duration(0.01f, 0.25f), gap(0.0f, 1.0f);
  std::vector<TimedPhoneme> out;
  float t = 0.05f;
  for (int i = 0; i < 120; ++i) {
    const float d = duration(rng);
    out.push_back({inventory[pick(rng)], t, t + d});
    t += d + (gap(rng) < 0.1f ? 0.3f * gap(rng) * 10.0f : 0.0f);
  }
  return out;
}

// --- Rule: mouth ownership ----------------------------------------------------

TEST(VisemeTrackRules, SpeechOwnsTheMouthThroughShortPausesAndGivesItBackInLongOnes) {
  // "ma (0.3 s) ma (1.2 s) ma": the comma-length pause stays speech's (closed
  // lips, no flash of the emotion's open mouth), the long one and the rests
  // around the line are the emotion's.
  std::vector<TimedPhoneme> line = phonemeRun({{"m", 0.08f}, {"a", 0.15f}}, 0.5f);
  for (const TimedPhoneme& p : phonemeRun({{"m", 0.08f}, {"a", 0.15f}}, 1.03f)) line.push_back(p);
  for (const TimedPhoneme& p : phonemeRun({{"m", 0.08f}, {"a", 0.15f}}, 2.46f)) line.push_back(p);
  const VisemeTrack track = buildOrDie(line);
  EXPECT_LT(sampleAt(track, track.startTime()).ownership, 0.01f);
  EXPECT_GT(sampleAt(track, 0.5f).ownership, 0.99f);    // the first phoneme: speech's
  EXPECT_GT(sampleAt(track, 0.88f).ownership, 0.99f);   // inside the 0.3 s pause
  EXPECT_GT(sampleAt(track, 0.88f)[Viseme::sil], 0.5f); // ... at rest, closed
  EXPECT_LT(sampleAt(track, 1.85f).ownership, 0.01f);   // the middle of the 1.2 s pause
  EXPECT_GT(sampleAt(track, 2.46f).ownership, 0.99f);   // back by the next phoneme
  EXPECT_LT(sampleAt(track, track.endTime()).ownership, 0.01f);
}

TEST(VisemeTrackRules, NoWeightChangesFasterThanTheRateBound) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const VisemeTrack track = buildOrDie(randomUtterance(seed));
    for (size_t c = 0; c < kSpeechChannelCount; ++c) {
      const auto keys = track.channelKeys(c);
      for (size_t k = 1; k < keys.size(); ++k) {
        const float rate = std::abs(keys[k].value - keys[k - 1].value) / (keys[k].time - keys[k - 1].time);
        ASSERT_LE(rate, kMaxWeightRate * 1.001f) << "channel " << c << " at " << keys[k].time << " s";
      }
    }
  }
}

TEST(VisemeTrackRules, WeightsStayInZeroOneAndSumToAboutOne) {
  const VisemeTrack track = buildOrDie(randomUtterance(7));
  for (float t = track.startTime(); t < track.endTime(); t += 0.0037f) {
    const Frame f = sampleAt(track, t);
    for (float w : f.visemes) ASSERT_TRUE(w >= 0.0f && w <= 1.0f) << w << " at " << t;
    for (float w : f.mouth) ASSERT_TRUE(w >= 0.0f && w <= 1.0f) << w << " at " << t;
    ASSERT_NEAR(f.sum(), 1.0f, 0.05f) << "at " << t;
  }
}

TEST(VisemeTrackRules, DiphthongsGlideFromTheirStartToTheirEnd) {
  const VisemeTrack track = buildOrDie(phonemeRun({{"t", 0.08f}, {"aɪ", 0.3f}, {"t", 0.08f}}));
  EXPECT_GT(sampleAt(track, 0.14f)[Viseme::aa], 0.6f);
  EXPECT_GT(sampleAt(track, 0.34f)[Viseme::I], 0.5f);
}

TEST(VisemeTrackRules, HTakesTheShapeOfTheVowelAfterIt) {
  const VisemeTrack track = buildOrDie(phonemeRun({{"_", 0.3f}, {"h", 0.08f}, {"u", 0.2f}}));
  EXPECT_GT(sampleAt(track, 0.34f)[Viseme::U], 0.5f);
}

TEST(VisemeTrackRules, ABorrowedBilabialShapeDoesNotCloseTheLips) {
  // "a h m a": h takes m's shape weakly, but only the m itself closes the lips.
  const VisemeTrack track = buildOrDie(phonemeRun({{"a", 0.2f}, {"h", 0.12f}, {"m", 0.08f}, {"a", 0.2f}}));
  EXPECT_LT(sampleAt(track, 0.23f)[MouthChannel::LipClosure], 0.9f);
  EXPECT_GT(sampleAt(track, 0.36f)[MouthChannel::LipClosure], 0.99f);
}

TEST(VisemeTrackRules, EspeakSentencesBuildWithoutWarnings) {
  // espeak-ng 1.51 --ipa of "Good evening. Here is the news.", "Bonjour, voici les nouvelles du soir."
  // and "Xin chào, đây là bản tin tối nay.", each phoneme 80 ms.
  for (const char* sentence : {"ɡˈʊd ˈiːvnɪŋ hˈiəɹ ɪz ðə njˈuːz", "bɔ̃ʒˈuʁ vwasˌi le- nuvˈɛl dy- swˈaʁ",
                               "sˈi1n tʃˈaː2w ɗˈəɪ1 lˌaː2 bˈaː4n t̪ˈi1n t̪ˈoɜj nˈa7j"}) {
    std::vector<TimedPhoneme> phonemes;
    for (const std::string& ipa : splitIpa(sentence))
      phonemes.push_back({ipa, 0.08f * phonemes.size(), 0.08f * (phonemes.size() + 1)});
    const auto built = VisemeTrackBuilder{}.build(phonemes);
    ASSERT_TRUE(built) << built.error().message;
    EXPECT_TRUE(built->warnings.empty()) << sentence << ": " << built->warnings.front();
    float jawLow = 1, jawHigh = 0;  // the jaw moves with the syllables
    for (float t = 0.1f; t < phonemes.back().end - 0.1f; t += 0.005f) {
      jawLow = std::min(jawLow, sampleAt(built->track, t)[MouthChannel::JawOpen]);
      jawHigh = std::max(jawHigh, sampleAt(built->track, t)[MouthChannel::JawOpen]);
    }
    EXPECT_GT(jawHigh - jawLow, 0.25f) << sentence;  // the English one has no open vowel
  }
}

// --- The builder's input ------------------------------------------------------

TEST(VisemeTrackBuilderInput, AnUnmappablePhonemeIsReportedNotDropped) {
  const auto built = VisemeTrackBuilder{}.build(phonemeRun({{"a", 0.2f}, {"☃", 0.1f}, {"a", 0.2f}}));
  ASSERT_TRUE(built) << built.error().message;
  ASSERT_EQ(built->warnings.size(), 1u);
  EXPECT_NE(built->warnings[0].find("phoneme 1 \"☃\" at 0.2 s"), std::string::npos) << built->warnings[0];
  EXPECT_GT(sampleAt(built->track, 0.25f)[Viseme::aa], 0.8f) << "its interval keeps its neighbours' shape";
}

TEST(VisemeTrackBuilderInput, MessagesStayOneLineWhateverThePhonemeHolds) {
  const auto built = VisemeTrackBuilder{}.build(phonemeRun({{"a", 0.2f}, {"\n\"☃", 0.1f}}));
  ASSERT_TRUE(built) << built.error().message;
  ASSERT_EQ(built->warnings.size(), 1u);
  EXPECT_EQ(built->warnings[0],
            "phoneme 1 \"\\u000a\\\"☃\" at 0.2 s: no viseme for its symbols; it takes its neighbours' shape");
}

TEST(VisemeTrackBuilderInput, RefusesBadTimesNamingThePhoneme) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const struct {
    std::vector<TimedPhoneme> phonemes;
    const char* expected;
  } cases[] = {
      {{{"a", 0.0f, 0.1f}, {"b", 0.05f, 0.2f}},
       "phoneme 1 \"b\": starts at 0.05 s, inside the previous cue (0 to 0.1 s): cues must not overlap"},
      {{{"a", 0.5f, 0.6f}, {"b", 0.1f, 0.2f}},
       "phoneme 1 \"b\": starts at 0.1 s, before the previous cue (0.5 s): cues must be in time order"},
      {{{"a", nan, 0.1f}}, "phoneme 0 \"a\": time is not a finite number"},
      {{{"a", 0.0f, inf}}, "phoneme 0 \"a\": time is not a finite number"},
      {{{"a", -0.5f, 0.1f}}, "phoneme 0 \"a\": negative start -0.5 s"},
      {{{"a", 0.3f, 0.3f}}, "phoneme 0 \"a\": ends at 0.3 s, not after its start 0.3 s"},
  };
  for (const auto& c : cases) {
    const auto built = VisemeTrackBuilder{}.build(c.phonemes);
    ASSERT_FALSE(built) << c.expected;
    EXPECT_EQ(built.error().kind, eng::ErrorKind::InvalidArgument);
    EXPECT_NE(built.error().message.find(c.expected), std::string::npos) << built.error().message;
  }
}

TEST(VisemeTrackBuilderInput, RefusesEmptyAndOverlongInput) {
  EXPECT_EQ(VisemeTrackBuilder{}.build(std::vector<TimedPhoneme>{}).error().kind, eng::ErrorKind::InvalidArgument);
  const auto late = VisemeTrackBuilder{}.build(std::vector<TimedPhoneme>{{"a", 0.0f, kMaxSpeechSeconds + 10.0f}});
  ASSERT_FALSE(late);
  EXPECT_EQ(late.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_NE(late.error().message.find("past the limit of 14400 s"), std::string::npos) << late.error().message;
}

TEST(VisemeTrackBuilderInput, VisemeCuesBuildTheSameWay) {
  const std::vector<TimedViseme> cues = {{Viseme::aa, 0.0f, 0.2f}, {Viseme::PP, 0.2f, 0.28f}, {Viseme::O, 0.28f, 0.5f}};
  const auto built = VisemeTrackBuilder{}.build(cues);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_GT(sampleAt(built->track, 0.24f)[Viseme::PP], 0.99f);
  EXPECT_GT(sampleAt(built->track, 0.4f)[Viseme::O], 0.7f);
  const std::vector<TimedViseme> overlapping = {{Viseme::aa, 0.0f, 0.2f}, {Viseme::PP, 0.1f, 0.28f}};
  EXPECT_NE(VisemeTrackBuilder{}
                .build(overlapping)
                .error()
                .message.find("viseme cue 1: starts at 0.1 s, inside the previous cue"),
            std::string::npos);
}

TEST(VisemeTrackBuilderInput, RefusesAVisemeOutsideTheSet) {
  const std::vector<TimedViseme> cues = {{static_cast<Viseme>(kVisemeCount), 0.0f, 0.2f}};
  const auto built = VisemeTrackBuilder{}.build(cues);
  ASSERT_FALSE(built);
  EXPECT_EQ(built.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_EQ(built.error().message, "viseme cue 0: viseme 15 is not one of the 15");
}

TEST(VisemeTrackBuilderInput, KeysAreSortedAndThinned) {
  const VisemeTrack track = buildOrDie(randomUtterance(11));
  size_t keys = 0;
  for (size_t c = 0; c < kSpeechChannelCount; ++c) {
    EXPECT_TRUE(validateKeys(track.channelKeys(c))) << "channel " << c;
    keys += track.channelKeys(c).size();
  }
  const size_t gridSamples =
      static_cast<size_t>((track.endTime() - track.startTime()) / kSampleStep) * kSpeechChannelCount;
  EXPECT_LT(keys, gridSamples / 2) << "thinning keeps well under half the grid";
}
