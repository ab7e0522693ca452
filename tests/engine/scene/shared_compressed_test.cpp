// The compressed files in ../shared/compressed load and match their
// uncompressed originals in ../shared/assets within the precision the
// compression keeps (skipped when ../shared is absent).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/model_check.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using scene_test::extensionRecord;
using testing_support::sharedDir;

size_t triangleCount(const eng::Model& model) {
  size_t n = 0;
  for (const eng::Mesh& mesh : model.meshes)
    for (const eng::Primitive& p : mesh.primitives) n += p.indices.size() / 3;
  return n;
}

// World-space bounds of every mesh instance with one named target fully applied.
eng::Aabb boundsWithTarget(const eng::Model& model, const std::string& target) {
  eng::Aabb box;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const int m = model.nodes[n].mesh;
    if (m < 0) continue;
    const eng::Mesh& mesh = model.meshes[m];
    const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), target);
    const glm::mat4 world = model.worldTransform(static_cast<int>(n));
    for (const eng::Primitive& p : mesh.primitives)
      for (size_t v = 0; v < p.vertexCount(); ++v) {
        glm::vec3 pos = p.positions[v];
        if (it != mesh.targetNames.end() && !p.targets[it - mesh.targetNames.begin()].positions.empty())
          pos += p.targets[it - mesh.targetNames.begin()].positions[v];
        box.extend(glm::vec3(world * glm::vec4(pos, 1.0f)));
      }
  }
  return box;
}

void expectBoxNear(const eng::Aabb& a, const eng::Aabb& b, float tolerance) {
  ASSERT_TRUE(a.valid() && b.valid());
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(a.min[c], b.min[c], tolerance) << "min axis " << c;
    EXPECT_NEAR(a.max[c], b.max[c], tolerance) << "max axis " << c;
  }
}

// Largest world-space length of one named target's position deltas.
float largestDelta(const eng::Model& model, const std::string& target) {
  float largest = 0.0f;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const int m = model.nodes[n].mesh;
    if (m < 0) continue;
    const eng::Mesh& mesh = model.meshes[m];
    const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), target);
    if (it == mesh.targetNames.end()) continue;
    const glm::mat4 world = model.worldTransform(static_cast<int>(n));
    for (const eng::Primitive& p : mesh.primitives)
      for (const glm::vec3& d : p.targets[it - mesh.targetNames.begin()].positions)
        largest = std::max(largest, glm::length(glm::vec3(world * glm::vec4(d, 0.0f))));
  }
  return largest;
}

TEST(SharedCompressed, RobotMeshoptMatchesTheUncompressedRobot) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model packed = scene_test::loadOk(sharedDir() / "compressed" / "RobotExpressive.meshopt.glb");
  const eng::Model original = scene_test::loadOk(sharedDir() / "assets" / "RobotExpressive.glb");
  ASSERT_EQ(packed.meshes.size(), original.meshes.size());
  std::printf("  meshopt: %zu vertices, %zu triangles; original: %zu vertices, %zu triangles\n",
              packed.totalVertexCount(), triangleCount(packed), original.totalVertexCount(), triangleCount(original));
  // gltfpack merges duplicate vertices and drops degenerate triangles.
  EXPECT_NEAR(double(packed.totalVertexCount()), double(original.totalVertexCount()), 0.03 * original.totalVertexCount());
  EXPECT_NEAR(double(triangleCount(packed)), double(triangleCount(original)), 0.01 * triangleCount(original));
  // 14-bit positions (gltfpack's default) over the robot's extent.
  const float tolerance = original.bounds().diagonal() / 4096.0f;
  expectBoxNear(packed.bounds(), original.bounds(), tolerance);

  const std::vector<std::string> expressions = {"Angry", "Surprised", "Sad"};
  for (const eng::Model* model : {&packed, &original}) {
    const auto head = std::find_if(model->meshes.begin(), model->meshes.end(),
                                   [](const eng::Mesh& m) { return !m.targetNames.empty(); });
    ASSERT_NE(head, model->meshes.end());
    EXPECT_EQ(head->targetNames, expressions);
  }
  for (const std::string& name : expressions) {
    SCOPED_TRACE(name);
    const float moved = largestDelta(original, name);
    EXPECT_GT(moved, 0.01f) << "the target moves the face";
    EXPECT_NEAR(largestDelta(packed, name), moved, tolerance + 0.01f * moved);
    expectBoxNear(boundsWithTarget(packed, name), boundsWithTarget(original, name), tolerance);
  }
  const eng::ExtensionUse* meshopt = extensionRecord(packed, "EXT_meshopt_compression");
  ASSERT_NE(meshopt, nullptr);
  EXPECT_TRUE(meshopt->required);
  EXPECT_EQ(meshopt->outcome.rfind("decoded", 0), 0u) << meshopt->outcome;
  ASSERT_NE(extensionRecord(packed, "KHR_mesh_quantization"), nullptr);
  EXPECT_TRUE(packed.warnings.empty()) << packed.warnings.front();
}

TEST(SharedCompressed, CesiumManDracoMatchesTheUncompressedCesiumMan) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model draco = scene_test::loadOk(sharedDir() / "compressed" / "CesiumMan-Draco" / "CesiumMan.gltf");
  const eng::Model original = scene_test::loadOk(sharedDir() / "assets" / "khronos" / "CesiumMan" / "glTF-Binary" / "CesiumMan.glb");
  ASSERT_EQ(draco.meshes.size(), 1u);
  ASSERT_EQ(original.meshes.size(), 1u);
  std::printf("  draco: %zu vertices, %zu triangles; original: %zu vertices, %zu triangles\n", draco.totalVertexCount(),
              triangleCount(draco), original.totalVertexCount(), triangleCount(original));
  EXPECT_EQ(triangleCount(draco), triangleCount(original));
  // Draco may split seam vertices, never merge them away.
  EXPECT_GE(draco.totalVertexCount(), original.totalVertexCount());
  expectBoxNear(draco.bounds(), original.bounds(), original.bounds().diagonal() / 4096.0f);
  const eng::Primitive& p = draco.meshes[0].primitives.at(0);
  EXPECT_EQ(p.texcoords.size(), p.vertexCount());
  for (const glm::vec2& uv : p.texcoords) {
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
  }
  for (const glm::vec3& n : p.normals) ASSERT_NEAR(glm::length(n), 1.0f, 0.02f);
  ASSERT_EQ(draco.images.size(), 1u);
  EXPECT_EQ(draco.materials.at(0).baseColorImage, 0);
  const eng::ExtensionUse* record = extensionRecord(draco, "KHR_draco_mesh_compression");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome, "decoded: 1 primitive(s) (Draco)");
}

// The Draco sample copied beside the test with its compressed stream damaged.
std::filesystem::path damagedCesiumMan(const std::string& name, const std::function<void(std::string& gltf,
                                                                                          std::vector<uint8_t>& bin)>& damage) {
  const auto source = sharedDir() / "compressed" / "CesiumMan-Draco";
  const auto dir = testing_support::freshTempDir(name);
  std::filesystem::copy_file(source / "CesiumMan.jpg", dir / "CesiumMan.jpg");
  std::string gltf = scene_test::readText(source / "CesiumMan.gltf");
  const std::string binText = scene_test::readText(source / "0.bin");
  std::vector<uint8_t> bin(binText.begin(), binText.end());
  damage(gltf, bin);
  scene_test::writeBytes(dir / "CesiumMan.gltf", std::vector<uint8_t>(gltf.begin(), gltf.end()));
  scene_test::writeBytes(dir / "0.bin", bin);
  return dir / "CesiumMan.gltf";
}

TEST(SharedCompressedBadInput, DamagedDracoStreamsAreRefusedInOneLine) {
  FACIAL_REQUIRE_SHARED();
  const nlohmann::json doc = nlohmann::json::parse(
      scene_test::readText(sharedDir() / "compressed" / "CesiumMan-Draco" / "CesiumMan.gltf"));
  const int view = doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
  const size_t offset = doc["bufferViews"][view].value("byteOffset", 0);
  const size_t length = doc["bufferViews"][view]["byteLength"];
  const std::string where = "mesh 0 primitive 0: the Draco stream";

  // Truncated: the view keeps only the first third of the stream.
  scene_test::expectLoadError(damagedCesiumMan("draco_truncated",
                                      [&](std::string& gltf, std::vector<uint8_t>&) {
                                        nlohmann::json edited = nlohmann::json::parse(gltf);
                                        edited["bufferViews"][view]["byteLength"] = length / 3;
                                        gltf = edited.dump();
                                      }),
                     where);
  // Not a Draco stream at all: the magic is overwritten.
  scene_test::expectLoadError(damagedCesiumMan("draco_magic", [&](std::string&, std::vector<uint8_t>& bin) {
                       std::fill(bin.begin() + offset, bin.begin() + offset + 8, uint8_t{0x5a});
                     }),
                     where);
  // Garbage after a valid header: refused or decoded to something the loader can check; never a crash.
  auto path = damagedCesiumMan("draco_garbled", [&](std::string&, std::vector<uint8_t>& bin) {
    for (size_t i = 32; i < length; ++i) bin[offset + i] = static_cast<uint8_t>(i * 131 + 7);
  });
  auto model = eng::loadModel(path);
  if (!model) {
    EXPECT_EQ(model.error().message.find('\n'), std::string::npos) << model.error().message;
    return;
  }
  // What decodes must still be in bounds: indices in range, finite vertices, matching counts.
  auto consistent = eng::checkModel(*model);
  EXPECT_TRUE(consistent.ok()) << (consistent ? "" : consistent.error().message);
}

}  // namespace
