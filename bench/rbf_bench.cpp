// RBF deformation cost: factoring a control layout, baking the influence
// matrix for a face-sized vertex set, and applying one displacement field
// (the per-frame part).
//   build/bin/facial_bench --benchmark_filter=Rbf
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "facial/runtime/rbf.h"

namespace {

std::vector<glm::vec3> randomPoints(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> points(count);
  for (glm::vec3& p : points) p = glm::vec3(u(rng), u(rng), u(rng));
  return points;
}

constexpr size_t kFaceVertices = 2694;  // facecap.glb's head mesh

void BM_RbfFactor(benchmark::State& state) {
  const std::vector<glm::vec3> controls = randomPoints(size_t(state.range(0)), 1);
  for (auto _ : state) {
    auto rbf = facial::RbfInterpolator::build(controls, facial::RbfKernel{});
    benchmark::DoNotOptimize(rbf);
  }
  state.SetLabel(std::to_string(state.range(0)) + " controls");
}
BENCHMARK(BM_RbfFactor)->Arg(16)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);

void BM_RbfBakeDeformer(benchmark::State& state) {
  const std::vector<glm::vec3> controls = randomPoints(size_t(state.range(0)), 2);
  const std::vector<glm::vec3> vertices = randomPoints(kFaceVertices, 3);
  const facial::RbfKernel kernel{facial::RbfKernelType::Polyharmonic, 1, 0.1f};
  for (auto _ : state) {
    auto deformer = facial::RbfDeformer::build(controls, vertices, kernel);
    benchmark::DoNotOptimize(deformer);
  }
  state.SetLabel(std::to_string(state.range(0)) + " controls -> " + std::to_string(kFaceVertices) + " vertices");
}
BENCHMARK(BM_RbfBakeDeformer)->Arg(16)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);

void BM_RbfApply(benchmark::State& state) {
  const std::vector<glm::vec3> controls = randomPoints(size_t(state.range(0)), 4);
  const std::vector<glm::vec3> vertices = randomPoints(kFaceVertices, 5);
  auto deformer = facial::RbfDeformer::build(controls, vertices, facial::RbfKernel{});
  if (!deformer) {
    state.SkipWithError(deformer.error().message.c_str());
    return;
  }
  const std::vector<glm::vec3> displacements = randomPoints(controls.size(), 6);
  const std::vector<float> mask(kFaceVertices, 0.5f);
  std::vector<glm::vec3> out(kFaceVertices);
  for (auto _ : state) {
    auto result = deformer->apply(displacements, out, mask);
    benchmark::DoNotOptimize(result);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kFaceVertices));
  state.SetLabel(std::to_string(state.range(0)) + " controls -> " + std::to_string(kFaceVertices) + " vertices");
}
BENCHMARK(BM_RbfApply)->Arg(16)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

}  // namespace
