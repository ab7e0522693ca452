// Timings from elsewhere: the project's phoneme and viseme JSON, Rhubarb Lip
// Sync (JSON, TSV), Azure viseme events and word timestamps. Each bad input
// fails with one line naming the source, where (JSON pointer or line) and what.
#include "facial/runtime/speech/speech_timings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "facial/runtime/speech/ipa_visemes.h"
#include "tests/facial/speech/speech_test_support.h"

using namespace facial;
using namespace facial::speech_test;

namespace {

template <class T>
void expectError(const eng::Result<T>& r, eng::ErrorKind kind, std::string_view message) {
  ASSERT_FALSE(r) << "expected: " << message;
  EXPECT_EQ(r.error().kind, kind) << r.error().message;
  EXPECT_EQ(r.error().message, message);
  EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rhubarb's README example ("Hi."), JSON and TSV.
constexpr const char* kRhubarbHiJson = R"({
  "metadata": {"soundFile": "C:\\hi.wav", "duration": 0.47},
  "mouthCues": [
    {"start": 0.00, "end": 0.05, "value": "X"}, {"start": 0.05, "end": 0.27, "value": "D"},
    {"start": 0.27, "end": 0.31, "value": "C"}, {"start": 0.31, "end": 0.43, "value": "B"},
    {"start": 0.43, "end": 0.47, "value": "X"}]})";
constexpr const char* kRhubarbHiTsv = "0.00\tX\n0.05\tD\n0.27\tC\n0.31\tB\n0.43\tX\n0.47\tX\n";

}  // namespace

TEST(SpeechTimings, ProjectPhonemeJson) {
  const auto p = phonemesFromJson(
      R"({"version": 1, "phonemes": [{"ipa": "h", "start": 0.0, "end": 0.06}, {"ipa": "ɛ", "start": 0.06, "end": 0.2},
          {"ipa": "l", "start": 0.2, "end": 0.26}, {"ipa": "oʊ", "start": 0.3, "end": 0.5}]})",
      "hello.json");
  ASSERT_TRUE(p) << p.error().message;
  ASSERT_EQ(p->size(), 4u);
  EXPECT_EQ((*p)[3].ipa, "oʊ");
  EXPECT_FLOAT_EQ((*p)[3].start, 0.3f);
  EXPECT_TRUE(VisemeTrackBuilder{}.build(*p));
}

TEST(SpeechTimings, ProjectPhonemeJsonProblems) {
  using K = eng::ErrorKind;
  expectError(
      phonemesFromJson(R"({"version": 2, "phonemes": []})", "a.json"), K::Unsupported,
      "a.json: /version: unsupported version 2: written by a newer release of facial (this build reads version 1)");
  expectError(phonemesFromJson(R"({"version": 1})", "a.json"), K::Malformed, "a.json: /: missing \"phonemes\"");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": []})", "a.json"), K::Malformed,
              "a.json: /phonemes: no cues");
  expectError(
      phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": "a", "start": 0, "end": 1, "stress": 1}]})", "a.json"),
      K::Malformed, "a.json: /phonemes/0/stress: unknown key (expected one of: ipa, start, end)");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": "a", "start": 0.5, "end": 0.6},
                                   {"ipa": "b", "start": 0.1, "end": 0.2}]})",
                               "a.json"),
              K::Malformed,
              "a.json: /phonemes/1: starts at 0.1 s, before the previous cue (0.5 s): cues must be in time order");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": "a", "start": -1, "end": 0.6}]})", "a.json"),
              K::Malformed, "a.json: /phonemes/0: negative start -1 s");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": "a", "start": 0, "end": 1e39}]})", "a.json"),
              K::Malformed, "a.json: /phonemes/0/end: number 1e+39 is not a finite float");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": "a", "start": 0, "end": 20000}]})", "a.json"),
              K::TooLarge, "a.json: /phonemes/0: ends at 20000 s, past the limit of 14400 s");
  expectError(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": 3, "start": 0, "end": 1}]})", "a.json"),
              K::Malformed, "a.json: /phonemes/0/ipa: expected a string, got number");
  const std::string three =
      R"({"version": 1, "phonemes": [{"ipa": "a", "start": 0, "end": 1}, {"ipa": "a", "start": 1, "end": 2},
                                {"ipa": "a", "start": 2, "end": 3}]})";
  expectError(phonemesFromJson(three, "a.json", 2), K::TooLarge, "a.json: /phonemes: 3 cues, over the limit of 2");
  EXPECT_FALSE(phonemesFromJson("{\"version\": 1, \"phonemes\": [", "a.json"));
}

TEST(SpeechTimings, ProjectVisemeJson) {
  const auto v = visemesFromJson(R"({"version": 1, "visemes": [{"viseme": "PP", "start": 0.1, "end": 0.18},
                                    {"viseme": "aa", "start": 0.18, "end": 0.4}]})",
                                 "v.json");
  ASSERT_TRUE(v) << v.error().message;
  ASSERT_EQ(v->size(), 2u);
  EXPECT_EQ((*v)[0].viseme, Viseme::PP);
  expectError(
      visemesFromJson(R"({"version": 1, "visemes": [{"viseme": "pp", "start": 0.1, "end": 0.18}]})", "v.json"),
      eng::ErrorKind::Malformed,
      "v.json: /visemes/0/viseme: unknown viseme (expected sil, PP, FF, TH, DD, kk, CH, SS, nn, RR, aa, E, I, O or U)");
}

TEST(SpeechTimings, RhubarbJsonAndTsvReadTheSameCues) {
  const auto json = rhubarbFromJson(kRhubarbHiJson, "hi.json");
  const auto tsv = rhubarbFromTsv(kRhubarbHiTsv, "hi.tsv");
  ASSERT_TRUE(json) << json.error().message;
  ASSERT_TRUE(tsv) << tsv.error().message;
  ASSERT_EQ(json->size(), 5u);
  ASSERT_EQ(tsv->size(), 5u);
  const Viseme expected[] = {Viseme::sil, Viseme::aa, Viseme::E, Viseme::SS, Viseme::sil};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ((*json)[i].viseme, expected[i]);
    EXPECT_EQ((*tsv)[i].viseme, expected[i]);
    EXPECT_FLOAT_EQ((*json)[i].start, (*tsv)[i].start);
    EXPECT_FLOAT_EQ((*json)[i].end, (*tsv)[i].end);
  }
  EXPECT_TRUE(rhubarbFromTsv("0.00\tX\r\n0.10\tA\r\n0.20\tX\r\n", "crlf.tsv")) << "Windows line ends";
}

TEST(SpeechTimings, RhubarbShapes) {
  const std::pair<char, Viseme> shapes[] = {{'A', Viseme::PP}, {'B', Viseme::SS}, {'C', Viseme::E},
                                            {'D', Viseme::aa}, {'E', Viseme::O},  {'F', Viseme::U},
                                            {'G', Viseme::FF}, {'H', Viseme::nn}, {'X', Viseme::sil}};
  for (const auto& [shape, viseme] : shapes) EXPECT_EQ(visemeForRhubarbShape(shape), viseme) << shape;
  EXPECT_FALSE(visemeForRhubarbShape('I'));
  EXPECT_FALSE(visemeForRhubarbShape('a'));
}

TEST(SpeechTimings, RhubarbProblems) {
  using K = eng::ErrorKind;
  expectError(rhubarbFromJson(R"({"mouthCues": [{"start": 0, "end": 0.1, "value": "Q"}]})", "r.json"), K::Malformed,
              "r.json: /mouthCues/0/value: unknown mouth shape \"Q\" (expected A, B, C, D, E, F, G, H or X)");
  expectError(
      rhubarbFromJson(
          R"({"mouthCues": [{"start": 0, "end": 0.1, "value": "X"}, {"start": 0.05, "end": 0.2, "value": "A"}]})",
          "r.json"),
      K::Malformed,
      "r.json: /mouthCues/1: starts at 0.05 s, inside the previous cue (0 to 0.1 s): cues must not overlap");
  expectError(rhubarbFromJson(R"({"metadata": {}})", "r.json"), K::Malformed, "r.json: /: missing \"mouthCues\"");
  expectError(rhubarbFromTsv("0.00\tX\n0.1\tQ\n0.2\tX\n", "r.tsv"), K::Malformed,
              "r.tsv: line 2: unknown mouth shape \"Q\" (expected A, B, C, D, E, F, G, H or X)");
  expectError(rhubarbFromTsv("0.00\tX\nabc\tA\n", "r.tsv"), K::Malformed,
              "r.tsv: line 2: \"abc\" is not a time in seconds");
  expectError(rhubarbFromTsv("0.00\tX\nnan\tA\n0.3\tX\n", "r.tsv"), K::Malformed,
              "r.tsv: line 2: time is not a finite number");
  expectError(rhubarbFromTsv("0.00\tX\n0.1\tA\ninf\tX\n", "r.tsv"), K::Malformed,
              "r.tsv: line 3: time is not a finite number");
  expectError(rhubarbFromTsv("0.00\tX\n0.30\tA\n0.10\tX\n", "r.tsv"), K::Malformed,
              "r.tsv: line 2: ends at 0.1 s, not after its start 0.3 s");
  expectError(rhubarbFromTsv("0.00 X", "r.tsv"), K::Malformed,
              "r.tsv: needs at least two lines: each starts a mouth shape, the last marks the end of the recording");
  expectError(rhubarbFromTsv("", "r.tsv"), K::Malformed,
              "r.tsv: needs at least two lines: each starts a mouth shape, the last marks the end of the recording");
  expectError(rhubarbFromTsv("0.00\n", "r.tsv"), K::Malformed,
              "r.tsv: line 1: expected a time and a mouth shape separated by a tab");
}

TEST(SpeechTimings, HugeInputIsRefusedWithTheLimitInTheMessage) {
  // The count is checked as lines are read, before the times are compared: the same line will do.
  std::string tsv;
  const std::string_view line = "0.5\tB\n";
  tsv.reserve(line.size() * (kMaxSpeechCues + 2));
  for (size_t i = 0; i <= kMaxSpeechCues + 1; ++i) tsv += line;
  const auto r = rhubarbFromTsv(tsv, "huge.tsv");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_EQ(r.error().message, "huge.tsv: line 1000002: 1000001 cues, over the limit of 1000000");
}

TEST(SpeechTimings, AzureVisemeEvents) {
  const auto ticks =
      azureVisemesFromJson(R"([{"visemeId": 0, "audioOffset": 0}, {"visemeId": 21, "audioOffset": 500000},
                                             {"visemeId": 2, "audioOffset": 1250000}, {"visemeId": 0, "audioOffset": 3000000}])",
                           "az.json");
  ASSERT_TRUE(ticks) << ticks.error().message;
  ASSERT_EQ(ticks->size(), 4u);
  EXPECT_EQ((*ticks)[1].viseme, Viseme::PP);
  EXPECT_FLOAT_EQ((*ticks)[1].start, 0.05f);
  EXPECT_FLOAT_EQ((*ticks)[1].end, 0.125f);
  EXPECT_FLOAT_EQ((*ticks)[3].end, 0.3f + kAzureLastEventSeconds);
  const auto ms =
      azureVisemesFromJson(R"([{"visemeId": 19, "offsetMs": 20}, {"visemeId": 0, "offsetMs": 95}])", "az.json");
  ASSERT_TRUE(ms) << ms.error().message;
  EXPECT_EQ((*ms)[0].viseme, Viseme::DD);
  EXPECT_FLOAT_EQ((*ms)[0].end, 0.095f);
  using K = eng::ErrorKind;
  expectError(azureVisemesFromJson(R"([{"visemeId": 22, "offsetMs": 0}])", "az.json"), K::Malformed,
              "az.json: /0/visemeId: viseme id 22 is not one of Azure's 0..21");
  expectError(azureVisemesFromJson(R"([{"visemeId": 1.5, "offsetMs": 0}])", "az.json"), K::Malformed,
              "az.json: /0/visemeId: viseme id 1.5 is not one of Azure's 0..21");
  expectError(azureVisemesFromJson(R"([{"visemeId": 1, "offsetMs": 0, "audioOffset": 0}])", "az.json"), K::Malformed,
              "az.json: /0: expected one of \"audioOffset\" (100-ns ticks) or \"offsetMs\" (milliseconds)");
  expectError(azureVisemesFromJson(R"([{"visemeId": 1, "offsetMs": 50}, {"visemeId": 2, "offsetMs": 50}])", "az.json"),
              K::Malformed, "az.json: /0: ends at 0.05 s, not after its start 0.05 s");
  expectError(azureVisemesFromJson(R"([])", "az.json"), K::Malformed, "az.json: /: no viseme events");
  expectError(azureVisemesFromJson(R"({"visemeId": 1})", "az.json"), K::Malformed,
              "az.json: /: expected an array, got object");
}

TEST(SpeechTimings, AzureIdsCoverTheSapiSet) {
  EXPECT_EQ(visemeForAzureId(0), Viseme::sil);
  EXPECT_EQ(visemeForAzureId(2), Viseme::aa);   // aa
  EXPECT_EQ(visemeForAzureId(7), Viseme::U);    // w uw
  EXPECT_EQ(visemeForAzureId(16), Viseme::CH);  // sh ch jh zh
  EXPECT_EQ(visemeForAzureId(18), Viseme::FF);  // f v
  EXPECT_EQ(visemeForAzureId(21), Viseme::PP);  // p b m
  EXPECT_FALSE(visemeForAzureId(-1));
  EXPECT_FALSE(visemeForAzureId(22));
}

// A cue whose text was read when its time fails: the text is freed (long
// enough to be on the heap; LeakSanitizer in tools/sanitizers/run.sh).
TEST(SpeechTimings, ACueWithABadTimeLeaksItsText) {
  const std::string longText = "a word well past the short-string buffer";
  EXPECT_FALSE(phonemesFromJson(R"({"version": 1, "phonemes": [{"ipa": ")" + longText + R"(", "start": 0, "end": "x"}]})",
                                "p.json"));
  EXPECT_FALSE(wordVisemesFromJson(R"({"words": [{"word": ")" + longText + R"(", "start": 0, "end": "x"}]})", "w.json"));
}

TEST(SpeechTimings, WordsAreSpreadOverTheirInterval) {
  EXPECT_EQ(visemesForWord("Good"), (std::vector<Viseme>{Viseme::kk, Viseme::U, Viseme::DD}));
  EXPECT_EQ(visemesForWord("chào"), (std::vector<Viseme>{Viseme::CH, Viseme::aa, Viseme::O}));
  EXPECT_EQ(visemesForWord("đây"), (std::vector<Viseme>{Viseme::DD, Viseme::aa, Viseme::I}));
  EXPECT_EQ(visemesForWord("thing"), (std::vector<Viseme>{Viseme::TH, Viseme::I, Viseme::nn}));
  EXPECT_TRUE(visemesForWord("42").empty());
  const auto cues = wordVisemesFromJson(R"({"words": [{"word": "Good", "start": 0.0, "end": 0.3, "probability": 0.9},
                                          {"word": "map", "start": 0.5, "end": 0.8}]})",
                                        "w.json");
  ASSERT_TRUE(cues) << cues.error().message;
  ASSERT_EQ(cues->size(), 6u);
  EXPECT_EQ((*cues)[0].viseme, Viseme::kk);
  EXPECT_FLOAT_EQ((*cues)[0].end, 0.1f);
  EXPECT_FLOAT_EQ((*cues)[2].end, 0.3f);
  EXPECT_EQ((*cues)[3].viseme, Viseme::PP);
  EXPECT_FLOAT_EQ((*cues)[3].start, 0.5f);
  EXPECT_TRUE(VisemeTrackBuilder{}.build(*cues));
  expectError(wordVisemesFromJson(R"({"words": [{"word": "!", "start": 0.0, "end": 0.3}]})", "w.json"),
              eng::ErrorKind::Malformed, "w.json: /: no word has a letter to speak");
  expectError(
      wordVisemesFromJson(
          R"({"words": [{"word": "a", "start": 0.0, "end": 0.3}, {"word": "b", "start": 0.2, "end": 0.4}]})", "w.json"),
      eng::ErrorKind::Malformed,
      "w.json: /words/1: starts at 0.2 s, inside the previous cue (0 to 0.3 s): cues must not overlap");
}

// The shared French recordings' Rhubarb output (../shared/speech, test use only).
TEST(SpeechTimings, SharedRecordingsRhubarbCues) {
  const std::filesystem::path dir = std::filesystem::path(FACIAL_SHARED_DIR) / "speech";
  if (!std::filesystem::exists(dir / "bonjour.json"))
    GTEST_SKIP() << "../shared is absent (" << dir << "): no Rhubarb recordings";
  for (const auto& [name, cueCount] : {std::pair{"bonjour.json", size_t{42}}, std::pair{"youpi.json", size_t{24}}}) {
    const auto cues = rhubarbFromJson(readFile(dir / name), name);
    ASSERT_TRUE(cues) << cues.error().message;
    EXPECT_EQ(cues->size(), cueCount) << name;
    const auto built = VisemeTrackBuilder{}.build(*cues);
    ASSERT_TRUE(built) << built.error().message;
    // Every A (closed) cue closes the lips; every long X rests; every long D opens the jaw.
    size_t closedCues = 0;
    for (const TimedViseme& cue : *cues) {
      const float middle = 0.5f * (cue.start + cue.end);
      const Frame f = sampleAt(built->track, middle);
      const bool closed = cue.viseme == Viseme::PP;
      const bool longRest = cue.viseme == Viseme::sil && cue.end - cue.start > 0.3f;
      const bool longWideOpen = cue.viseme == Viseme::aa && cue.end - cue.start > 0.1f;
      EXPECT_TRUE(!closed || f[MouthChannel::LipClosure] > 0.99f) << name << " A at " << cue.start;
      EXPECT_TRUE(!longRest || f[Viseme::sil] > 0.9f) << name << " X at " << cue.start;
      EXPECT_TRUE(!longWideOpen || f[MouthChannel::JawOpen] > 0.5f) << name << " D at " << cue.start;
      closedCues += closed ? 1 : 0;
    }
    EXPECT_GT(closedCues, 3u) << name << ": the recordings have A cues (4 and 8)";
  }
}

// Broken input of any shape is an error of one line, never a crash.
TEST(SpeechTimings, RandomBytesAreRefusedInOneLine) {
  std::mt19937 rng(3);
  const std::string alphabet = "0123456789.\t\n -eEXABnaif{}[]\":,visemeIdstartendmouthCuesword\xc3\xa9\xff";
  std::uniform_int_distribution<size_t> length(0, 48), letter(0, alphabet.size() - 1);
  for (int i = 0; i < 3000; ++i) {
    std::string text;
    for (size_t n = length(rng); n > 0; --n) text += alphabet[letter(rng)];
    for (const auto& r : {rhubarbFromTsv(text, "x"), rhubarbFromJson(text, "x"), azureVisemesFromJson(text, "x"),
                          wordVisemesFromJson(text, "x"), visemesFromJson(text, "x")})
      ASSERT_TRUE(r || r.error().message.find('\n') == std::string::npos) << r.error().message;
    const auto phonemes = phonemesFromJson(text, "x");
    ASSERT_TRUE(phonemes || phonemes.error().message.find('\n') == std::string::npos) << phonemes.error().message;
    for (const std::string& phoneme : splitIpa(text)) (void)visemesForIpa(phoneme);
  }
}
