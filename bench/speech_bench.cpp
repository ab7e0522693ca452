// Lip sync cost: building a viseme track for a 10,000-character text's worth
// of phonemes (about ten minutes of speech), and sampling it once per frame
// at 60 Hz over its whole length (the per-frame part; it allocates nothing).
//   build/bin/facial_bench --benchmark_filter=Speech
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "facial/runtime/speech/viseme_track.h"
#include "tests/common/allocation_counter.h"

namespace {

using namespace facial;

// A realistic phoneme stream: words of 2-9 letters made of (C)(C)V(C)
// syllables at conversational durations (consonants 40-90 ms, vowels
// 70-160 ms, some diphthongs), a 60-120 ms comma pause now and then and a
// 250-450 ms pause after each sentence of 8-16 words, until `characters`
// characters of text (letters and spaces) are spoken.
std::vector<TimedPhoneme> synthesiseSpeech(size_t characters, uint32_t seed) {
  const char* consonants[] = {"p", "b", "m",  "f",  "v", "θ", "ð", "t", "d", "n", "l", "s",
                              "z", "ʃ", "tʃ", "dʒ", "k", "ɡ", "ŋ", "ɹ", "w", "j", "h"};
  const char* vowels[] = {"a",  "ɑː", "æ", "ɛ",  "e",  "ɪ",  "iː", "ɒ",  "ɔː", "ʊ",
                          "uː", "ʌ",  "ə", "ɜː", "aɪ", "eɪ", "oʊ", "aʊ", "ɔɪ"};
  std::mt19937 rng(seed);
  const auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  const auto pick = [&](const auto& list) {
    return list[std::uniform_int_distribution<size_t>(0, std::size(list) - 1)(rng)];
  };
  std::vector<TimedPhoneme> out;
  float t = 0.2f;
  size_t written = 0, wordsInSentence = 0, sentenceLength = 12;
  while (written < characters) {
    const size_t letters = std::uniform_int_distribution<size_t>(2, 9)(rng);
    for (size_t spoken = 0; spoken < letters;) {  // syllables until the word's letters are spoken
      const bool onset = uniform(0, 1) < 0.8f, coda = uniform(0, 1) < 0.4f;
      const auto add = [&](const char* ipa, float duration) {
        out.push_back({ipa, t, t + duration});
        t += duration;
        ++spoken;
      };
      if (onset) add(pick(consonants), uniform(0.04f, 0.09f));
      add(pick(vowels), uniform(0.07f, 0.16f));
      if (coda) add(pick(consonants), uniform(0.04f, 0.09f));
    }
    written += letters + 1;
    if (++wordsInSentence == sentenceLength) {
      t += uniform(0.25f, 0.45f);
      wordsInSentence = 0;
      sentenceLength = std::uniform_int_distribution<size_t>(8, 16)(rng);
    } else if (uniform(0, 1) < 0.1f) {
      t += uniform(0.06f, 0.12f);
    }
  }
  return out;
}

constexpr size_t kTextCharacters = 10'000;

void BM_SpeechBuildTrack(benchmark::State& state) {
  const std::vector<TimedPhoneme> phonemes = synthesiseSpeech(kTextCharacters, 1);
  size_t keys = 0;
  for (auto _ : state) {
    auto built = VisemeTrackBuilder{}.build(phonemes);
    if (!built) state.SkipWithError(built.error().message.c_str());
    keys = built->track.keyCount();
    benchmark::DoNotOptimize(built);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(phonemes.size()));
  state.counters["phonemes"] = static_cast<double>(phonemes.size());
  state.counters["speech_s"] = phonemes.back().end;
  state.counters["keys"] = static_cast<double>(keys);
  state.SetLabel("items = phonemes");
}
BENCHMARK(BM_SpeechBuildTrack)->Unit(benchmark::kMillisecond);

void BM_SpeechSampleFrame(benchmark::State& state) {
  const std::vector<TimedPhoneme> phonemes = synthesiseSpeech(kTextCharacters, 1);
  const VisemeTrack track = VisemeTrackBuilder{}.build(phonemes)->track;
  std::array<uint32_t, kSpeechChannelCount> cursors{};
  std::array<float, kVisemeCount> visemes{};
  std::array<float, kMouthChannelCount> mouth{};
  const float frame = 1.0f / 60.0f, length = track.endTime() - track.startTime();
  float t = 0;
  const uint64_t allocationsBefore = testing_support::allocationCount();
  for (auto _ : state) {
    // Forward playback at 60 Hz, looping back to the start at the end (a seek).
    VisemeSampleJob{
        .track = &track, .time = track.startTime() + t, .cursors = cursors, .visemes = visemes, .mouth = mouth}
        .Run();
    benchmark::DoNotOptimize(visemes.data());
    t += frame;
    if (t > length) t = 0;
  }
  state.counters["allocations"] = static_cast<double>(testing_support::allocationCount() - allocationsBefore);
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("items = frames (15 visemes + 3 mouth channels)");
}
BENCHMARK(BM_SpeechSampleFrame);

}  // namespace
