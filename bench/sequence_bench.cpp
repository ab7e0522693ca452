// A video rendered headless, one frame at a time against frames in flight
// (app::recordSequence with OffscreenOptions::framesInFlight 1 or
// app::kSequenceFramesInFlight), on one device or two taking turns
// (app::SequenceRenderers' lanes): the built-in head, every target on its own
// sine, 512x512 at 30 fps, each frame read back and H.264-encoded
// (audio::VideoWriter, on its own thread). Counter x_realtime: clip seconds
// per wall second (> 1 is faster than real time). On a loaded machine run
// them alternately and compare their ratios (docs/performance.md):
//   for r in 1 2 3; do for a in in_flight:1/lanes:1 in_flight:3/lanes:1 in_flight:3/lanes:2; do
//     build/bin/facial_bench --benchmark_filter="VideoSequence/$a/"; done; done
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/sequence_recorder.h"
#include "audio/video_writer.h"

namespace {

constexpr float kFps = 30.0f;
constexpr float kClipSeconds = 3.0f;

eng::Result<void> recordClip(app::SequenceRenderers& renderers, const std::filesystem::path& out) {
  auto writer = audio::VideoWriter::create(out, {.width = 512, .height = 512, .framesPerSecond = kFps});
  if (!writer) return writer.error();
  std::vector<float> weights(renderers.gpuModel(0).weightCount());
  eng::vk::ModelInstance instance{&renderers.gpuModel(0), glm::mat4(1.0f), {}};
  eng::Result<void> written;
  auto summary = app::recordSequence(
      renderers.lanes(), {.framesPerSecond = kFps, .seconds = kClipSeconds, .progressLabel = "bench"},
      [&](const app::FrameContext& f) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        if (!written) return written.error();
        instance.model = &renderers.gpuModel(f.lane);
        for (size_t t = 0; t < weights.size(); ++t)
          weights[t] = 0.3f + 0.3f * std::sin(f.time * 4.0f + 0.7f * float(t));
        instance.weights = weights;
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      },
      [&](const app::FrameContext&, const eng::Image& image) {
        if (written) written = writer->addFrame(image.rgba8);
      });
  if (!summary) return summary.error();
  if (!written) return written.error();
  return writer->finish();
}

void BM_VideoSequence(benchmark::State& state) {
  auto setup = app::FaceSetup::load();
  if (!setup) return state.SkipWithError(setup.error().message.c_str());
  auto renderers = app::SequenceRenderers::create(
      setup->displayModel(),
      {.width = 512, .height = 512, .quality = eng::vk::RenderQuality::Balanced, .framesInFlight = uint32_t(state.range(0))},
      uint32_t(state.range(1)));
  if (!renderers) return state.SkipWithError(renderers.error().message.c_str());
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "facial_bench_sequence.mp4";
  for (auto _ : state) {
    if (auto recorded = recordClip(*renderers, out); !recorded) return state.SkipWithError(recorded.error().message.c_str());
  }
  std::filesystem::remove(out);
  state.counters["x_realtime"] =
      benchmark::Counter(kClipSeconds * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VideoSequence)
    ->ArgNames({"in_flight", "lanes"})
    ->Args({1, 1})
    ->Args({app::kSequenceFramesInFlight, 1})
    ->Args({app::kSequenceFramesInFlight, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
