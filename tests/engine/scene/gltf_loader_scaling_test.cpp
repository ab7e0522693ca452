// Loading a glTF does work linear in what the file holds (issue 37): files
// grown in targets, nodes, skinned nodes, accessors, animations, images and
// extension names load with ~4x the work at 4x the size, not ~16x. The work
// is what the loader counts (eng::countWork: joint checks, extension names)
// plus every heap allocation of the load, tinygltf's parse included; the
// bytes allocated and charged to the budget must grow linearly too.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/work_scaling.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using scene_test::GltfFileBuilder;
using scene_test::Json;

struct LoadCost {
  uint64_t allocatedBytes = 0;
  size_t charged = 0;
};

// expectLinearWork over loading file(n): the loader's counted steps plus its allocations.
void expectLinearLoad(const std::function<GltfFileBuilder(size_t)>& file, size_t n) {
  std::map<size_t, LoadCost> costs;
  testing_support::expectLinearWork([&](size_t size) {
    const std::vector<uint8_t> bytes = file(size).glbBytes();
    eng::resetWorkCount();  // the loading, not the making of the file
    const uint64_t allocated = testing_support::allocatedBytes();
    size_t charged = 0;
    testing_support::countAllocationsAsWork([&] {
      auto model = eng::loadModelFromBytes(bytes, "scaling.glb", {}, &charged);
      EXPECT_TRUE(model) << model.error().message;
    });
    costs[size] = {testing_support::allocatedBytes() - allocated, charged};
  }, n);
  const LoadCost& small = costs[n];
  const LoadCost& large = costs[4 * n];
  EXPECT_LE(large.allocatedBytes, 5 * small.allocatedBytes) << "bytes allocated at n = " << n;
  EXPECT_LE(large.charged, 5 * small.charged) << "bytes charged at n = " << n;
}

std::vector<glm::vec3> lift(size_t vertex) {
  std::vector<glm::vec3> deltas(4, glm::vec3(0.0f));
  deltas[vertex % 4].z = 1.0f;
  return deltas;
}

GltfFileBuilder quadWithTargets(size_t targets) {
  GltfFileBuilder file = scene_test::quadWithTarget();
  Json& prim = file.doc["meshes"][0]["primitives"][0];
  Json names = Json::array(), weights = Json::array();
  prim["targets"] = Json::array();
  for (size_t t = 0; t < targets; ++t) {
    prim["targets"].push_back({{"POSITION", file.addVec3(lift(t), true)}});
    names.push_back("target_" + std::to_string(t));
    weights.push_back(0.0);
  }
  file.doc["meshes"][0]["extras"]["targetNames"] = names;
  file.doc["meshes"][0]["weights"] = weights;
  return file;
}

TEST(GltfLoaderScaling, TargetsAreLinear) { expectLinearLoad(quadWithTargets, 200); }

// A binary tree of named nodes, each drawing the quad.
TEST(GltfLoaderScaling, NodesAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file = scene_test::quadWithTarget();
    file.doc["nodes"] = Json::array();
    for (size_t i = 0; i < n; ++i) {
      Json node = {{"mesh", 0}, {"name", "node_" + std::to_string(i)}, {"translation", {0, 1, 0}}};
      for (size_t child : {2 * i + 1, 2 * i + 2})
        if (child < n) node["children"].push_back(child);
      file.doc["nodes"].push_back(node);
    }
    file.doc["scenes"] = {{{"nodes", {0}}}};
    return file;
  }, 500);
}

// n nodes drawing one skinned mesh of 3n vertices: the joints of each (mesh,
// skin) pair are checked once, not once a node (nodes x vertices).
TEST(GltfLoaderScaling, NodesSharingASkinnedMeshAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file;
    std::vector<glm::vec3> positions;
    for (size_t v = 0; v < 3 * n; ++v) positions.push_back({float(v % 3), float(v / 3), 0.0f});
    const int pos = file.addVec3(positions, true);
    const std::vector<uint8_t> joints(4 * positions.size(), 0);
    std::vector<float> weights(4 * positions.size(), 0.0f);
    for (size_t v = 0; v < positions.size(); ++v) weights[4 * v] = 1.0f;
    const int j = file.addAccessor(file.addView(joints), scene_test::kUnsignedByte, positions.size(), "VEC4");
    const int w = file.addAccessor(file.addView(weights), scene_test::kFloat, positions.size(), "VEC4");
    const Json attributes = {{"POSITION", pos}, {"JOINTS_0", j}, {"WEIGHTS_0", w}};
    file.doc["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", attributes}}})}}});
    file.doc["nodes"] = Json::array({{{"name", "joint"}}});
    for (size_t i = 0; i < n; ++i) file.doc["nodes"].push_back({{"mesh", 0}, {"skin", 0}});
    file.doc["skins"] = Json::array({{{"joints", {0}}}});
    Json roots = Json::array();
    for (size_t i = 0; i <= n; ++i) roots.push_back(i);
    file.doc["scenes"] = {{{"nodes", roots}}};
    file.doc["scene"] = 0;
    return file;
  }, 300);
}

// One mesh of n primitives, each a triangle with its own position accessor.
TEST(GltfLoaderScaling, AccessorsAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file;
    Json primitives = Json::array();
    for (size_t p = 0; p < n; ++p) {
      const int pos = file.addVec3({{0, 0, float(p)}, {1, 0, float(p)}, {0, 1, float(p)}}, true);
      primitives.push_back({{"attributes", {{"POSITION", pos}}}});
    }
    file.addMeshWithNode({{"primitives", primitives}});
    return file;
  }, 300);
}

// n animations of the quad's target weight, each with its own key accessors.
TEST(GltfLoaderScaling, AnimationsAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file = scene_test::quadWithTarget();
    file.doc["animations"] = Json::array();
    for (size_t a = 0; a < n; ++a) {
      const int times = file.addScalars({0.0f, 1.0f, 2.0f});
      const int values = file.addScalars({0.0f, 1.0f, 0.0f});
      file.doc["animations"].push_back(
          {{"name", "clip_" + std::to_string(a)},
           {"samplers", Json::array({{{"input", times}, {"output", values}}})},
           {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}})}});
    }
    return file;
  }, 300);
}

// n different 2x2 PNGs, each drawn by its own material: each decoded once.
TEST(GltfLoaderScaling, ImagesAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file = scene_test::quadWithTarget();
    for (size_t i = 0; i < n; ++i) {
      std::vector<uint8_t> rgba;  // distinct pixels make distinct bytes
      for (int p = 0; p < 4; ++p) rgba.insert(rgba.end(), {uint8_t(i), uint8_t(i >> 8), 0, 255});
      auto png = eng::encodePng(2, 2, rgba);
      EXPECT_TRUE(png) << png.error().message;
      if (!png) return file;
      const std::vector<uint8_t>& bytes = *png;
      file.doc["images"].push_back({{"bufferView", file.addView(bytes)}, {"mimeType", "image/png"}});
      file.doc["textures"].push_back({{"source", i}});
      file.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
    }
    return file;
  }, 100);
}

// n unknown optional extensions, and a handled one required n times.
TEST(GltfLoaderScaling, ExtensionNamesAreLinear) {
  expectLinearLoad([](size_t n) {
    GltfFileBuilder file = scene_test::quadWithTarget();
    for (size_t i = 0; i < n; ++i) {
      file.doc["extensionsUsed"].push_back("EXT_unknown_" + std::to_string(i));
      file.doc["extensionsRequired"].push_back("KHR_materials_unlit");
    }
    return file;
  }, 2000);
}

}  // namespace
