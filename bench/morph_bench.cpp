// Morphing cost: the CPU baseline (the classic per-vertex lerp that rewrites
// the whole vertex buffer every frame, eng::morphPrimitiveCpu) against the
// GPU path (deltas resident in storage buffers, the vertex shader sums only
// the active (target, weight) pairs), on the built-in head (36k vertices,
// 21 targets) and on a 256-target grid. The argument is the number of
// non-zero weights. GPU numbers are whole offscreen frames (draw + resolve +
// read-back) at 256x256 on whatever device Vulkan picks (FACIAL_DEVICE to
// force one; on lavapipe that "GPU" is the CPU too).
//   build/bin/facial_bench --benchmark_filter=Morph
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "engine/view/framing_bounds.h"
#include "bench/bench_gpu.h"
#include "importers/face_dressing.h"
#include "tests/common/test_meshes.h"

namespace {

const eng::Model& headModel() {
  static const eng::Model model = [] {
    auto loaded = eng::loadModel(std::string(FACIAL_SOURCE_DIR) + "/data/head.glb");
    if (!loaded) {
      std::fprintf(stderr, "morph_bench: %s\n", loaded.error().message.c_str());
      return eng::Model{};
    }
    return std::move(*loaded);
  }();
  return model;
}

// A 100x100 grid (10,201 vertices) with 256 dense targets: every target moves
// every vertex, the worst case for the CPU lerp.
const eng::Model& gridModel() {
  static const eng::Model model = [] {
    constexpr int kSide = 101, kTargets = 256;
    eng::Primitive p = testing_support::flatSheet(kSide);
    eng::Mesh mesh;
    for (int t = 0; t < kTargets; ++t) {
      eng::MorphTarget target;
      for (const glm::vec3& v : p.positions)
        target.positions.emplace_back(0.0f, 0.0f, 0.01f * std::sin(6.0f * v.x + 0.37f * t) * std::cos(5.0f * v.y));
      target.normals.assign(p.positions.size(), glm::vec3(0.0f));
      p.targets.push_back(std::move(target));
      mesh.targetNames.push_back("t" + std::to_string(t));
    }
    mesh.defaultWeights.assign(kTargets, 0.0f);
    mesh.primitives.push_back(std::move(p));
    return testing_support::singleMeshModel(std::move(mesh), "procedural 256-target grid");
  }();
  return model;
}

// Flat weights with the first `active` at 0.5, the rest zero.
std::vector<float> weightsWithActive(const eng::Model& model, int64_t active) {
  std::vector<float> weights(eng::WeightLayout(model).total(), 0.0f);
  for (int64_t i = 0; i < active && i < int64_t(weights.size()); ++i) weights[size_t(i)] = 0.5f;
  return weights;
}

void cpuMorph(benchmark::State& state, const eng::Model& model) {
  if (model.meshes.empty()) return state.SkipWithError("model did not load");
  const std::vector<float> weights = weightsWithActive(model, state.range(0));
  const eng::WeightLayout layout(model);
  std::vector<glm::vec3> positions, normals;
  size_t vertices = 0;
  for (auto _ : state) {
    vertices = 0;
    for (size_t m = 0; m < model.meshes.size(); ++m) {
      const std::span<const float> meshWeights(weights.data() + layout.offset(int(m)), layout.count(int(m)));
      for (const eng::Primitive& p : model.meshes[m].primitives) {
        positions.resize(p.vertexCount());
        normals.resize(p.vertexCount());
        eng::morphPrimitiveCpu(p, meshWeights, positions, normals);
        vertices += p.vertexCount();
      }
    }
    benchmark::DoNotOptimize(positions.data());
  }
  state.counters["vertices"] = double(vertices);
}

void gpuMorphFrame(benchmark::State& state, const eng::Model& model) {
  bench::GpuBench& g = bench::gpu();
  if (!g.renderer) return state.SkipWithError(("Vulkan: " + g.error).c_str());
  if (model.meshes.empty()) return state.SkipWithError("model did not load");
  // Drawn as the programs draw it: an untextured face dressed for display.
  const std::optional<eng::Model> dressed = importers::dressedForDisplay(model);
  auto gpuModel = g.renderer->upload(dressed ? *dressed : model);
  if (!gpuModel) return state.SkipWithError(gpuModel.error().message.c_str());
  const std::vector<float> weights = weightsWithActive(model, state.range(0));
  eng::vk::SceneView view;
  view.camera = eng::OrbitCamera::frame(eng::framingBounds(model), 1.0f);
  const eng::vk::ModelInstance instance{&gpuModel.value(), glm::mat4(1.0f), weights};
  for (auto _ : state) {
    auto image = g.renderer->render(view, {&instance, 1});
    if (!image) return state.SkipWithError(image.error().message.c_str());
    benchmark::DoNotOptimize(image->rgba8.data());
  }
  state.SetLabel(g.context->deviceInfo().name);
}

void BM_CpuMorphHead(benchmark::State& state) { cpuMorph(state, headModel()); }
BENCHMARK(BM_CpuMorphHead)->Arg(0)->Arg(4)->Arg(21)->Unit(benchmark::kMicrosecond);
void BM_CpuMorphGrid256(benchmark::State& state) { cpuMorph(state, gridModel()); }
BENCHMARK(BM_CpuMorphGrid256)->Arg(0)->Arg(16)->Arg(256)->Unit(benchmark::kMicrosecond);
void BM_GpuMorphHeadFrame(benchmark::State& state) { gpuMorphFrame(state, headModel()); }
BENCHMARK(BM_GpuMorphHeadFrame)->Arg(0)->Arg(4)->Arg(21)->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_GpuMorphGrid256Frame(benchmark::State& state) { gpuMorphFrame(state, gridModel()); }
BENCHMARK(BM_GpuMorphGrid256Frame)->Arg(0)->Arg(16)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
