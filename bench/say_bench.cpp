// `facial say` end to end and its speech synthesis, on a 10-second English
// news item: the program itself run as a child (the same code path as a
// user's command: synthesis, track, rendering, encoding), 512x512 at 30 fps
// with sound, and espeak-ng's synthesis alone. Counters: the clip's seconds
// and times real time (clip seconds per wall second; > 1 is faster than real time).
//   build/bin/facial_bench --benchmark_filter=Say
//   FACIAL_DEVICE=cpu build/bin/facial_bench --benchmark_filter=SayEndToEnd   (lavapipe)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "audio/speech_synthesis.h"

namespace {

// About 10.5 s at espeak-ng's normal English rate (11.4 s with the clip's rest at the end).
constexpr const char* kNewsItem =
    "Good evening. Here is the news. The weather will be mild and bright across the country tomorrow, "
    "with a light breeze from the west. Markets closed a little higher today, and the trains are running on time.";

void BM_SaySynthesis(benchmark::State& state) {
  double seconds = 0, wall = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto speech = audio::synthesize(kNewsItem);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!speech) return state.SkipWithError(speech.error().message.c_str());
    seconds = speech->durationSeconds();
    benchmark::DoNotOptimize(speech->samples.data());
  }
  state.counters["speech_s"] = seconds;
  state.counters["x_realtime"] = seconds * double(state.iterations()) / wall;
}
BENCHMARK(BM_SaySynthesis)->Unit(benchmark::kMillisecond)->UseRealTime();

// The "N frames (S s at F fps)" of say's summary line; 0 when absent.
double clipSeconds(const std::string& summary) {
  const size_t open = summary.find(" frames (");
  return open == std::string::npos ? 0.0 : std::atof(summary.c_str() + open + 9);
}

void BM_SayEndToEnd(benchmark::State& state) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "facial_bench_say.mp4";
  const std::string command = std::string("'") + FACIAL_PROGRAM + "' say \"" + kNewsItem +
                              "\" --size 512x512 --fps 30 --out '" + out.string() + "' 2>/dev/null";
  double clip = 0, wall = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    FILE* child = popen(command.c_str(), "r");
    if (!child) return state.SkipWithError("cannot start facial");
    std::string summary;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, child)) summary += buffer;
    if (pclose(child) != 0) return state.SkipWithError(("facial say failed: " + summary).c_str());
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    wall += took;
    state.SetIterationTime(took);
    clip = clipSeconds(summary);
  }
  std::filesystem::remove(out);
  state.counters["clip_s"] = clip;
  state.counters["x_realtime"] = clip * double(state.iterations()) / wall;
}
// One run takes 15-30 s on lavapipe: one iteration unless --benchmark_min_time asks for more.
BENCHMARK(BM_SayEndToEnd)->Unit(benchmark::kSecond)->UseManualTime()->Iterations(1);

}  // namespace
