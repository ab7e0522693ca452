// Morph paths swept over vertices {5k, 25k, 50k, 100k} x active targets
// {4, 12, 52} x instances {1, 8, 64} on a synthetic face-like mesh: a grid
// with 52 targets, each moving its own band of a fifth of the vertices (face
// rigs are local: a brow target leaves the mouth alone), position and normal
// deltas. Per frame and path, the morph stage only (no rasterisation):
//   MorphSweep/cpu_lerp    the CPU baseline: every instance's whole vertex
//                          buffer rewritten by eng::morphPrimitiveCpu and
//                          copied into a mapped Vulkan buffer;
//   MorphSweep/cpu_sparse  compacted deltas: per target only the vertices it
//                          moves (index + deltas), added onto a copy of the
//                          rest mesh, then the same copy;
//   MorphSweep/gpu_morph   the renderer's path, as each frame runs it once:
//                          sparse deltas resident, the compute pre-pass
//                          (morph.comp) sums each vertex's entries with the
//                          instance's weights into the morphed-vertex buffer;
//   MorphSweep/gpu_vs      the pre-pass plus the capture pass that reads the
//                          morphed vertices in the vertex shader and stores
//                          them (rasteriser discard);
//   MorphSweep/static      the capture pass with every weight zero (no pre-pass).
// GPU paths are timed by GPU timestamps where the device has them.
// Counters: verts, active, instances, delta_bytes (deltas read per frame),
// gbps (delta_bytes / time). MorphCopyBandwidth times vkCmdCopyBuffer of
// 256 MiB on the same device: the ratio gbps / copy_gbps says how close a
// path comes to the device's own bandwidth.
//   build/bin/facial_bench --benchmark_filter=MorphSweep --benchmark_format=json
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/weights.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "bench/bench_gpu.h"
#include "tests/common/test_meshes.h"

namespace {

constexpr int kTargets = 52;
constexpr int kBands = 5;  // a target moves one band: a fifth of the vertices

// A square grid of about `vertices` vertices with kTargets local targets.
eng::Model sweepModel(int vertices) {
  const int side = std::max(2, int(std::lround(std::sqrt(double(vertices)))));
  eng::Primitive p = testing_support::flatSheet(side);
  eng::Mesh mesh;
  const size_t n = p.positions.size();
  for (int t = 0; t < kTargets; ++t) {
    eng::MorphTarget target;
    target.positions.assign(n, glm::vec3(0.0f));
    target.normals.assign(n, glm::vec3(0.0f));
    const size_t begin = n * size_t(t % kBands) / kBands, end = n * size_t(t % kBands + 1) / kBands;
    for (size_t v = begin; v < end; ++v) {
      const glm::vec3& q = p.positions[v];
      target.positions[v] = {0.0f, 0.0f, 0.01f * std::sin(6.0f * q.x + 0.37f * float(t)) * std::cos(5.0f * q.y)};
      target.normals[v] = {0.05f * std::cos(6.0f * q.x + 0.37f * float(t)), 0.0f, 0.0f};
    }
    p.targets.push_back(std::move(target));
    mesh.targetNames.push_back("t" + std::to_string(t));
  }
  mesh.defaultWeights.assign(kTargets, 0.0f);
  mesh.primitives.push_back(std::move(p));
  return testing_support::singleMeshModel(std::move(mesh), "sweep grid " + std::to_string(n) + " vertices");
}

const eng::Model& cachedModel(int vertices) {
  static std::map<int, eng::Model> models;
  auto it = models.find(vertices);
  if (it == models.end()) {
    if (!models.empty()) models.clear();  // one size at a time: 100k x 52 targets is ~250 MB
    it = models.emplace(vertices, sweepModel(vertices)).first;
  }
  return it->second;
}

std::vector<float> weightsWithActive(int active) {
  std::vector<float> weights(kTargets, 0.0f);
  for (int i = 0; i < active; ++i) weights[size_t(i)] = 0.5f;
  return weights;
}

// Compacted deltas of one target: the vertices it moves and by how much.
struct SparseTarget {
  std::vector<uint32_t> vertices;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
};

std::vector<SparseTarget> compact(const eng::Primitive& p) {
  std::vector<SparseTarget> sparse(p.targets.size());
  for (size_t t = 0; t < p.targets.size(); ++t) {
    for (uint32_t v = 0; v < p.positions.size(); ++v) {
      const glm::vec3 dp = p.targets[t].positions[v], dn = p.targets[t].normals[v];
      if (dp == glm::vec3(0.0f) && dn == glm::vec3(0.0f)) continue;
      sparse[t].vertices.push_back(v);
      sparse[t].positions.push_back(dp);
      sparse[t].normals.push_back(dn);
    }
  }
  return sparse;
}

void setCounters(benchmark::State& state, size_t vertices, int active, int instances, double deltaBytes) {
  state.counters["verts"] = double(vertices);
  state.counters["active"] = active;
  state.counters["instances"] = instances;
  state.counters["delta_bytes"] = deltaBytes;
  state.counters["gbps"] = benchmark::Counter(deltaBytes * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

// CPU paths: each instance morphed on the CPU, then its vertices (position +
// normal) copied into the mapped buffer the draw would read.
void cpuPath(benchmark::State& state, bool sparse) {
  bench::GpuBench& v = bench::gpu();
  if (!v.context) return state.SkipWithError(("Vulkan: " + v.error).c_str());
  const int active = int(state.range(1)), instances = int(state.range(2));
  const eng::Primitive& p = cachedModel(int(state.range(0))).meshes[0].primitives[0];
  const size_t n = p.vertexCount();
  const std::vector<float> weights = weightsWithActive(active);
  const std::vector<SparseTarget> compacted = sparse ? compact(p) : std::vector<SparseTarget>{};
  auto staging = eng::vk::Buffer::create(*v.context, VkDeviceSize(n) * 24 * VkDeviceSize(instances),
                                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, eng::vk::MemoryUsage::Upload,
                                         "cpu-morphed vertices");
  if (!staging) return state.SkipWithError(staging.error().message.c_str());
  std::vector<glm::vec3> positions(n), normals(n);
  std::byte* out = staging->mapped();
  for (auto _ : state) {
    for (int k = 0; k < instances; ++k) {
      if (!sparse) {
        eng::morphPrimitiveCpu(p, weights, positions, normals);
      } else {
        std::copy(p.positions.begin(), p.positions.end(), positions.begin());
        std::copy(p.normals.begin(), p.normals.end(), normals.begin());
        for (int t = 0; t < active; ++t) {
          const SparseTarget& s = compacted[size_t(t)];
          const float w = weights[size_t(t)];
          for (size_t i = 0; i < s.vertices.size(); ++i) {
            positions[s.vertices[i]] += w * s.positions[i];
            normals[s.vertices[i]] += w * s.normals[i];
          }
        }
        for (glm::vec3& nrm : normals) nrm = glm::normalize(nrm);
      }
      std::byte* slice = out + size_t(k) * n * 24;
      std::memcpy(slice, positions.data(), n * 12);
      std::memcpy(slice + n * 12, normals.data(), n * 12);
    }
    benchmark::DoNotOptimize(out);
  }
  double deltaBytes = 0.0;
  if (!sparse) {
    deltaBytes = double(active) * double(n) * 24.0;
  } else {
    for (int t = 0; t < active; ++t) deltaBytes += double(compacted[size_t(t)].vertices.size()) * 28.0;
  }
  setCounters(state, n, active, instances, deltaBytes * instances);
}

enum class GpuStage { Morph, MorphAndCapture };

// A GPU path (or the static pass: active 0), timed by GPU timestamps.
void gpuPath(benchmark::State& state, bool morph, GpuStage stage = GpuStage::MorphAndCapture) {
  bench::GpuBench& v = bench::gpu();
  if (!v.renderer) return state.SkipWithError(("Vulkan: " + v.error).c_str());
  if (stage == GpuStage::MorphAndCapture && !v.renderer->canCapture())
    return state.SkipWithError("the device cannot store from vertex shaders");
  const int active = morph ? int(state.range(1)) : 0, instances = int(state.range(2));
  const eng::Model& model = cachedModel(int(state.range(0)));
  auto gpuModel = v.renderer->upload(model);
  if (!gpuModel) return state.SkipWithError(gpuModel.error().message.c_str());
  const std::vector<float> weights = weightsWithActive(active);
  std::vector<eng::vk::ModelInstance> list(size_t(instances), {&*gpuModel, glm::mat4(1.0f), weights});
  auto timed = [&] {
    return stage == GpuStage::Morph ? v.renderer->morphTimed(list) : v.renderer->captureTimed(list);
  };
  if (auto warm = timed(); !warm) return state.SkipWithError(warm.error().message.c_str());
  double wallSeconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto ms = timed();
    const auto end = std::chrono::steady_clock::now();
    if (!ms) return state.SkipWithError(ms.error().message.c_str());
    wallSeconds += std::chrono::duration<double>(end - start).count();
    state.SetIterationTime(*ms ? **ms * 1e-3 : std::chrono::duration<double>(end - start).count());
  }
  // Submit-and-wait on the CPU clock (prepare included), beside the GPU time.
  state.counters["wall_ms"] = wallSeconds * 1e3 / double(std::max<int64_t>(1, state.iterations()));
  // Sparse entries read: 32 bytes per (vertex, target) pair that moves, for
  // every target (the pre-pass reads a vertex's entries, skipping zero weights).
  const eng::Primitive& p = model.meshes[0].primitives[0];
  const size_t n = p.vertexCount();
  double moved = 0.0;
  for (const eng::MorphTarget& t : p.targets)
    moved += double(std::count_if(t.positions.begin(), t.positions.end(), [](const glm::vec3& d) { return d != glm::vec3(0.0f); }));
  setCounters(state, n, int(state.range(1)), instances, active > 0 ? moved * 32.0 * instances : 0.0);
}

void sweepArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"verts", "active", "instances"});
  for (int vertices : {5000, 25000, 50000, 100000})
    for (int active : {4, 12, 52})
      for (int instances : {1, 8, 64}) b->Args({vertices, active, instances});
}

void MorphSweep_cpu_lerp(benchmark::State& state) { cpuPath(state, false); }
void MorphSweep_cpu_sparse(benchmark::State& state) { cpuPath(state, true); }
void MorphSweep_gpu_morph(benchmark::State& state) { gpuPath(state, true, GpuStage::Morph); }
void MorphSweep_gpu_vs(benchmark::State& state) { gpuPath(state, true); }
void MorphSweep_static(benchmark::State& state) { gpuPath(state, false); }
BENCHMARK(MorphSweep_cpu_lerp)->Apply(sweepArgs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MorphSweep_cpu_sparse)->Apply(sweepArgs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MorphSweep_gpu_morph)->Apply(sweepArgs)->Unit(benchmark::kMillisecond)->UseManualTime();
BENCHMARK(MorphSweep_gpu_vs)->Apply(sweepArgs)->Unit(benchmark::kMillisecond)->UseManualTime();
BENCHMARK(MorphSweep_static)->Apply(sweepArgs)->Unit(benchmark::kMillisecond)->UseManualTime();

// The device's own copy bandwidth: vkCmdCopyBuffer between two device-local
// buffers of 256 MiB (read + write counted once each, as a copy's GB/s is
// usually quoted by bytes copied: gbps = bytes / time).
void MorphCopyBandwidth(benchmark::State& state) {
  bench::GpuBench& v = bench::gpu();
  if (!v.context) return state.SkipWithError(("Vulkan: " + v.error).c_str());
  constexpr VkDeviceSize kBytes = VkDeviceSize(256) << 20;
  auto src = eng::vk::Buffer::create(*v.context, kBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                     eng::vk::MemoryUsage::GpuOnly, "copy source");
  auto dst = eng::vk::Buffer::create(*v.context, kBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     eng::vk::MemoryUsage::GpuOnly, "copy destination");
  if (!src || !dst) return state.SkipWithError("could not create the copy buffers");
  auto copy = [&] {
    return v.context->submitOneShot([&](VkCommandBuffer cmd) {
      const VkBufferCopy region{0, 0, kBytes};
      vkCmdCopyBuffer(cmd, src->handle(), dst->handle(), 1, &region);
    });
  };
  // Untimed first copy: on a CPU device it faults the pages in.
  if (auto warm = copy(); !warm) return state.SkipWithError(warm.error().message.c_str());
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto done = copy();
    const auto end = std::chrono::steady_clock::now();
    if (!done) return state.SkipWithError(done.error().message.c_str());
    // The wall clock around submit-and-wait: lavapipe's timestamps bracket a
    // copy it has not finished (they read 0.1 ms for 256 MiB).
    state.SetIterationTime(std::chrono::duration<double>(end - start).count());
  }
  state.counters["gbps"] = benchmark::Counter(double(kBytes) * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(v.context->deviceInfo().name);
}
BENCHMARK(MorphCopyBandwidth)->Unit(benchmark::kMillisecond)->UseManualTime();

}  // namespace
