// Dataset images per second per core: one item of data/datasets/example.json
// (the built-in head, its emotion, random action units, pose, light rig and
// backdrop) rendered headless, its landmarks followed on the morphed mesh,
// encoded as PNG with its label line, at 128, 256 and 512 pixels. Disk writes
// are left out (a few tens of KB per item). Counters:
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
  auto renderer = dataset::ItemRenderer::create(*spec, 0, device ? device : "");
  if (!renderer) return state.SkipWithError(renderer.error().message.c_str());
  uint64_t k = 0;
  size_t bytes = 0;
  const double cpuStart = processCpuSeconds();
  for (auto _ : state) {
    auto item = renderer->render(dataset::sampleItem(*spec, k++ % spec->count));
    if (!item) return state.SkipWithError(item.error().message.c_str());
    auto png = eng::encodePng(item->image.width, item->image.height, item->image.rgba8);
    if (!png) return state.SkipWithError(png.error().message.c_str());
    bytes += png->size() + dataset::labelJson(item->label).size();
  }
  const double cpu = processCpuSeconds() - cpuStart;
  state.counters["images_per_core_s"] = cpu > 0.0 ? double(state.iterations()) / cpu : 0.0;
  state.counters["images_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bytes_per_image"] = double(bytes) / double(std::max<int64_t>(state.iterations(), 1));
  state.SetLabel(renderer->deviceName());
}
BENCHMARK(BM_DatasetItem)->Arg(128)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace
