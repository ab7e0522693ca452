// OBJ keyframe conversion speed on a 100k-vertex face-sized set: parsing,
// strict conversion, conversion with --match-by-position on a re-ordered
// export, and writing the GLB. The set is generated once into a temp folder.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "engine/scene/gltf_writer.h"
#include "importers/obj_keyframes.h"
#include "importers/obj_mesh.h"

namespace {

constexpr int kSide = 316;  // 317 x 317 = 100,489 vertices, 99,856 quads
constexpr int kObjTargets = 4;

void appendFloat(std::string& s, float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

// A wavy grid; target t lifts a disc of vertices. `order` permutes the vertex lines.
std::string gridObj(int target, const std::vector<int>& order) {
  const int row = kSide + 1, n = row * row;
  std::vector<int> lineOf(n);
  for (int k = 0; k < n; ++k) lineOf[order[k]] = k + 1;
  std::string s;
  s.reserve(static_cast<size_t>(n) * 90);
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    const float x = static_cast<float>(i % row) / kSide, y = static_cast<float>(i / row) / kSide;
    float z = 0.05f * std::sin(x * 12.0f) * std::cos(y * 9.0f);
    if (target >= 0) {
      const float cx = 0.2f + 0.2f * target, cy = 0.5f;
      const float d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      if (d2 < 0.01f) z += 0.1f * (0.01f - d2) / 0.01f;
    }
    s += "v ";
    appendFloat(s, x);
    s += ' ';
    appendFloat(s, y);
    s += ' ';
    appendFloat(s, z);
    s += '\n';
  }
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    s += "vt ";
    appendFloat(s, static_cast<float>(i % row) / kSide);
    s += ' ';
    appendFloat(s, static_cast<float>(i / row) / kSide);
    s += '\n';
  }
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const int a = y * row + x, b = a + 1, c = a + row + 1, d = a + row;
      s += "f";
      for (int v : {a, b, c, d}) {
        const std::string idx = std::to_string(lineOf[v]);
        s += ' ';
        s += idx;
        s += '/';
        s += idx;
      }
      s += '\n';
    }
  return s;
}

struct ObjSet {
  std::filesystem::path dir;
  std::vector<importers::ObjTargetFile> targets;
  std::vector<importers::ObjTargetFile> shuffledTargets;
};

const ObjSet& objSet() {
  static const ObjSet set = [] {
    ObjSet s;
    s.dir = std::filesystem::temp_directory_path() / "facial_obj_convert_bench";
    std::filesystem::create_directories(s.dir);
    const int n = (kSide + 1) * (kSide + 1);
    std::vector<int> identity(n), shuffled(n);
    std::iota(identity.begin(), identity.end(), 0);
    shuffled = identity;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(11));
    auto write = [&](const std::string& name, int target, const std::vector<int>& order) {
      std::ofstream(s.dir / name, std::ios::binary) << gridObj(target, order);
      return s.dir / name;
    };
    write("neutral.obj", -1, identity);
    for (int t = 0; t < kObjTargets; ++t) {
      const std::string name = "shape" + std::to_string(t);
      s.targets.push_back({name, write(name + ".obj", t, identity)});
      s.shuffledTargets.push_back({name, write(name + "_shuffled.obj", t, shuffled)});
    }
    return s;
  }();
  return set;
}

void BM_ReadObj(benchmark::State& state) {
  const ObjSet& set = objSet();
  size_t vertices = 0;
  for (auto _ : state) {
    auto mesh = importers::readObjPolygonMesh(set.dir / "neutral.obj");
    if (!mesh) state.SkipWithError(mesh.error().message.c_str());
    vertices = mesh ? mesh->positions.size() : 0;
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(vertices), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadObj)->Unit(benchmark::kMillisecond);

void convert(benchmark::State& state, bool shuffledTargets) {
  const ObjSet& set = objSet();
  const importers::ObjKeyframeOptions options{.matchByPosition = shuffledTargets};
  size_t vertices = 0;
  for (auto _ : state) {
    auto imported = importers::importObjKeyframes(set.dir / "neutral.obj", shuffledTargets ? set.shuffledTargets : set.targets, options);
    if (!imported) {
      state.SkipWithError(imported.error().message.c_str());
      break;
    }
    vertices = imported->model.totalVertexCount();
    benchmark::DoNotOptimize(imported);
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["targets"] = kObjTargets;
}

void BM_ConvertObjSet(benchmark::State& state) { convert(state, false); }
BENCHMARK(BM_ConvertObjSet)->Unit(benchmark::kMillisecond);

void BM_ConvertObjSetMatchByPosition(benchmark::State& state) { convert(state, true); }
BENCHMARK(BM_ConvertObjSetMatchByPosition)->Unit(benchmark::kMillisecond);

void BM_SaveConvertedGlb(benchmark::State& state) {
  const ObjSet& set = objSet();
  auto imported = importers::importObjKeyframes(set.dir / "neutral.obj", set.targets);
  if (!imported) {
    state.SkipWithError(imported.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    auto saved = eng::saveModel(imported->model, set.dir / "face.glb");
    if (!saved) state.SkipWithError(saved.error().message.c_str());
  }
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(set.dir / "face.glb"));
}
BENCHMARK(BM_SaveConvertedGlb)->Unit(benchmark::kMillisecond);

}  // namespace
