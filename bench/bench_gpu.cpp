#include "bench/bench_gpu.h"

namespace bench {

GpuBench& gpu() {
  static GpuBench bench = [] {
    GpuBench b;
    auto ctx = eng::vk::Context::create({});
    if (!ctx) {
      b.error = ctx.error().message;
      return b;
    }
    b.context = std::make_unique<eng::vk::Context>(std::move(*ctx));
    auto renderer = eng::vk::OffscreenRenderer::create(*b.context, {.width = 256, .height = 256});
    if (!renderer) {
      b.error = renderer.error().message;
      return b;
    }
    b.renderer = std::make_unique<eng::vk::OffscreenRenderer>(std::move(*renderer));
    return b;
  }();
  return bench;
}

}  // namespace bench
