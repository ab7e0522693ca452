// Dataset images per second per core: items of data/datasets/example.json
// (the built-in head, its emotion, random action units, pose, light rig and
// backdrop) rendered headless, their landmarks followed on the morphed mesh,
// encoded as PNG with their label lines, at 128, 256 and 512 pixels, as
// `facial dataset` makes them: items in flight on the devices taking turns
// (ItemRenderer; the second argument 1: one device, one item at a time, as
// before). Disk writes are left out (a few tens of KB per item). Counters:
//   images_per_s      wall clock, the whole process (lavapipe's threads included)
//   images_per_core_s images per second of process CPU time: what one core of
//                     a cluster node makes (the cost model in docs/dataset.md)
//   build/bin/facial_bench --benchmark_filter=DatasetItem
// On a GPU (FACIAL_DEVICE picks one) the same benchmark gives images per GPU.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>

#include "app/face_setup.h"
#include "dataset/dataset_spec.h"
#include "dataset/item_label.h"
#include "dataset/item_renderer.h"
#include "engine/scene/image_io.h"

namespace {

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

void BM_DatasetItem(benchmark::State& state) {
  auto spec = dataset::readDatasetSpec(app::dataDirectory() / "datasets" / "example.json");
  if (!spec) return state.SkipWithError(spec.error().message.c_str());
  spec->width = spec->height = uint32_t(state.range(0));
  const char* device = std::getenv("FACIAL_DEVICE");
  const bool oneAtATime = state.range(1) == 1;
  dataset::ItemRendererOptions options{.device = device ? device : ""};
  if (oneAtATime) options.lanes = options.framesInFlight = 1;
  auto renderer = dataset::ItemRenderer::create(*spec, 0, options);
  if (!renderer) return state.SkipWithError(renderer.error().message.c_str());
  uint64_t k = 0;
  size_t bytes = 0;
  const double cpuStart = processCpuSeconds();
  // Each iteration submits one item and, once the pipeline is full, writes the oldest.
  const auto writeOldest = [&]() -> bool {
    auto item = renderer->collect();
    if (!item) {
      state.SkipWithError(item.error().message.c_str());
      return false;
    }
    auto png = eng::encodePng(item->image.width, item->image.height, item->image.rgba8);
    if (!png) {
      state.SkipWithError(png.error().message.c_str());
      return false;
    }
    bytes += png->size() + dataset::labelJson(item->label).size();
    return true;
  };
  for (auto _ : state) {
    if (renderer->full() && !writeOldest()) return;
    if (auto submitted = renderer->submit(dataset::sampleItem(*spec, k++ % spec->count)); !submitted)
      return state.SkipWithError(submitted.error().message.c_str());
  }
  while (renderer->pending() > 0)
    if (!writeOldest()) return;
  const double cpu = processCpuSeconds() - cpuStart;
  state.counters["images_per_core_s"] = cpu > 0.0 ? double(state.iterations()) / cpu : 0.0;
  state.counters["images_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bytes_per_image"] = double(bytes) / double(std::max<int64_t>(state.iterations(), 1));
  state.SetLabel(renderer->deviceName());
}
BENCHMARK(BM_DatasetItem)
    ->ArgNames({"size", "one_at_a_time"})
    ->ArgsProduct({{128, 256, 512}, {0, 1}})
    ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace
