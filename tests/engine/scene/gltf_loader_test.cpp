// glTF import results on files the tests write themselves: sparse and
// quantized accessors, primitive modes, generated normals, hierarchy,
// names/weights, animations, materials and images.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using scene_test::GltfFileBuilder;
using scene_test::Json;
using namespace scene_test;
using testing_support::freshTempDir;

void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(GltfLoader, ReadsQuadTargetNamesAndDefaultWeightsFromGltfAndGlb) {
  const auto dir = freshTempDir("loader_quad");
  GltfFileBuilder b = quadWithTarget();
  b.writeGltf(dir / "external.gltf", "external.bin");
  b.writeGltf(dir / "datauri.gltf");
  b.writeGlb(dir / "binary.glb");
  for (const char* name : {"external.gltf", "datauri.gltf", "binary.glb"}) {
    const eng::Model model = loadOk(dir / name);
    ASSERT_EQ(model.meshes.size(), 1u) << name;
    const eng::Mesh& mesh = model.meshes[0];
    EXPECT_EQ(mesh.name, "Quad");
    EXPECT_EQ(mesh.targetNames, std::vector<std::string>{"lift"});
    EXPECT_EQ(mesh.defaultWeights, std::vector<float>{0.25f});
    const eng::Primitive& prim = mesh.primitives.at(0);
    EXPECT_EQ(prim.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(prim.targets.size(), 1u);
    EXPECT_EQ(prim.targets[0].positions[2], glm::vec3(0, 0, 1));
    EXPECT_TRUE(prim.targets[0].normals.empty()) << "the file morphs no normals";
    EXPECT_EQ(model.roots, std::vector<int>{0});
    EXPECT_TRUE(model.warnings.empty());
  }
}

TEST(GltfLoader, SparseTargetWithoutBufferViewIsZerosPlusSubstitutions) {
  const auto dir = freshTempDir("loader_sparse_zero_base");
  GltfFileBuilder b = quadWithTarget();
  const std::vector<uint8_t> indices = {1, 3};
  const std::vector<glm::vec3> values = {{0.5f, 0, 0}, {0, -2, 0}};
  const int iv = b.addView(indices);
  const int vv = b.addView(values);
  const int sparse = b.addAccessor(-1, kFloat, 4, "VEC3");
  b.doc["accessors"][sparse]["sparse"] = {{"count", 2},
                                          {"indices", {{"bufferView", iv}, {"componentType", kUnsignedByte}}},
                                          {"values", {{"bufferView", vv}}}};
  b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = sparse;
  b.writeGltf(dir / "sparse.gltf", "sparse.bin");
  const eng::Model model = loadOk(dir / "sparse.gltf");
  const auto& deltas = model.meshes.at(0).primitives.at(0).targets.at(0).positions;
  EXPECT_EQ(deltas, (std::vector<glm::vec3>{{0, 0, 0}, {0.5f, 0, 0}, {0, 0, 0}, {0, -2, 0}}));
}

TEST(GltfLoader, SparseOverABaseBufferViewReplacesOnlyListedElements) {
  const auto dir = freshTempDir("loader_sparse_base");
  GltfFileBuilder b = quadWithTarget();
  const std::vector<glm::vec3> base(4, glm::vec3(1, 1, 1));
  const std::vector<uint32_t> indices = {0};
  const std::vector<glm::vec3> values = {{9, 8, 7}};
  const int bv = b.addView(base);
  const int iv = b.addView(indices);
  const int vv = b.addView(values);
  const int acc = b.addAccessor(bv, kFloat, 4, "VEC3");
  b.doc["accessors"][acc]["sparse"] = {{"count", 1},
                                       {"indices", {{"bufferView", iv}, {"componentType", kUnsignedInt}}},
                                       {"values", {{"bufferView", vv}}}};
  b.doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"] = acc;
  b.writeGlb(dir / "sparse_base.glb");
  const eng::Model model = loadOk(dir / "sparse_base.glb");
  const auto& normals = model.meshes.at(0).primitives.at(0).targets.at(0).normals;
  EXPECT_EQ(normals, (std::vector<glm::vec3>{{9, 8, 7}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}));
}

TEST(GltfLoader, DecodesQuantizedNormalizedAndIntegerComponents) {
  const auto dir = freshTempDir("loader_quantized");
  GltfFileBuilder b;
  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  // Positions: unsigned shorts, not normalized, 6 bytes padded to an 8-byte stride.
  struct PackedPos { uint16_t x, y, z, pad; };
  const std::vector<PackedPos> pos = {{0, 0, 0, 0}, {100, 0, 0, 0}, {0, 200, 0, 0}};
  const int posAcc = b.addAccessor(b.addView(pos, 8), kUnsignedShort, 3, "VEC3");
  // Normals: normalized signed bytes (127 -> 1, -128 clamps to -1), padded to 4 bytes.
  const std::vector<int8_t> nrm = {0, 0, 127, 0, 0, -128, 0, 0, 64, 0, 0, 0};
  const int nrmAcc = b.addAccessor(b.addView(nrm, 4), kByte, 3, "VEC3", true);
  // Texcoords: normalized unsigned shorts.
  const std::vector<uint16_t> uv = {0, 65535, 65535, 0, 32768, 32768};
  const int uvAcc = b.addAccessor(b.addView(uv), kUnsignedShort, 3, "VEC2", true);
  // Target deltas: normalized shorts, 8-byte stride.
  const std::vector<int16_t> delta = {32767, 0, 0, 0, 0, -32768, 0, 0, 0, 0, 16384, 0};
  const int deltaAcc = b.addAccessor(b.addView(delta, 8), kShort, 3, "VEC3", true);
  // Indices: unsigned bytes.
  const std::vector<uint8_t> idx = {0, 1, 2};
  const int idxAcc = b.addAccessor(b.addView(idx), kUnsignedByte, 3, "SCALAR");
  b.addMeshWithNode({{"primitives", Json::array({{{"attributes", {{"POSITION", posAcc}, {"NORMAL", nrmAcc},
                                                                  {"TEXCOORD_0", uvAcc}}},
                                                   {"indices", idxAcc},
                                                   {"targets", Json::array({{{"POSITION", deltaAcc}}})}}})}});
  b.writeGlb(dir / "quantized.glb");
  const eng::Model model = loadOk(dir / "quantized.glb");
  const eng::Primitive& p = model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(p.positions, (std::vector<glm::vec3>{{0, 0, 0}, {100, 0, 0}, {0, 200, 0}}));
  expectNear(p.normals[0], {0, 0, 1});
  expectNear(p.normals[1], {0, -1, 0});
  expectNear(p.normals[2], {64.0f / 127.0f, 0, 0});
  EXPECT_NEAR(p.texcoords[0].y, 1.0f, 1e-6f);
  EXPECT_NEAR(p.texcoords[2].x, 32768.0f / 65535.0f, 1e-6f);
  expectNear(p.targets[0].positions[0], {1, 0, 0});
  expectNear(p.targets[0].positions[1], {0, -1, 0});
  expectNear(p.targets[0].positions[2], {0, 0, 16384.0f / 32767.0f});
  EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(model.warnings.empty());
}

// COLOR_0 (a scan's or a sculpt's paint): VEC3 or VEC4, float or normalized
// unsigned; linear RGBA out, alpha 1 for VEC3. Other kinds are skipped.
TEST(GltfLoader, ReadsVertexColoursOfEveryKindTheSpecAllows) {
  const auto dir = freshTempDir("loader_colours");
  GltfFileBuilder b;
  const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, true);
  const std::vector<uint8_t> rgb8 = {255, 0, 0, 0, 0, 0, 0, 0, 0, 128, 255, 0};  // 4-byte stride
  const int rgbAcc = b.addAccessor(b.addView(rgb8.data(), 12, 4), kUnsignedByte, 3, "VEC3", true);
  const std::vector<uint16_t> rgba16 = {0, 65535, 0, 32768, 65535, 65535, 65535, 65535, 0, 0, 0, 0};
  const int rgbaAcc = b.addAccessor(b.addView(rgba16), kUnsignedShort, 3, "VEC4", true);
  const std::vector<float> rgbaF = {0.25f, 0.5f, 0.75f, 1.0f, 2.0f, -1.0f, 0.5f, 0.5f, 0, 0, 0, 1};
  const int floatAcc = b.addAccessor(b.addView(rgbaF), kFloat, 3, "VEC4");
  const int rawAcc = b.addAccessor(b.addView(rgb8.data(), 12, 4), kUnsignedByte, 3, "VEC3");  // not normalized
  auto prim = [&](int colours) { return Json{{"attributes", {{"POSITION", pos}, {"COLOR_0", colours}}}}; };
  b.addMeshWithNode({{"primitives", Json::array({prim(rgbAcc), prim(rgbaAcc), prim(floatAcc), prim(rawAcc)})}});
  b.writeGltf(dir / "colours.gltf");
  const eng::Model model = loadOk(dir / "colours.gltf");
  const auto& prims = model.meshes.at(0).primitives;
  ASSERT_EQ(prims.size(), 4u);
  ASSERT_EQ(prims[0].colors.size(), 3u);
  EXPECT_EQ(prims[0].colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(prims[0].colors[2], glm::vec4(0.0f, 128.0f / 255.0f, 1.0f, 1.0f));
  EXPECT_EQ(prims[0].colors[2].a, 1.0f) << "VEC3 colours are opaque";
  ASSERT_EQ(prims[1].colors.size(), 3u);
  EXPECT_NEAR(prims[1].colors[0].a, 32768.0f / 65535.0f, 1e-6f);
  EXPECT_EQ(prims[1].colors[1], glm::vec4(1.0f));
  ASSERT_EQ(prims[2].colors.size(), 3u);
  EXPECT_EQ(prims[2].colors[0], glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
  EXPECT_EQ(prims[2].colors[1], glm::vec4(1.0f, 0.0f, 0.5f, 0.5f)) << "clamped to [0, 1]";
  EXPECT_TRUE(prims[3].colors.empty());
  EXPECT_TRUE(hasWarningContaining(model, "mesh 0 primitive 3 COLOR_0 is not a VEC3 or VEC4"));
  EXPECT_EQ(model.warnings.size(), 1u);
}

TEST(GltfLoader, VertexColoursShortOfThePrimitivesVerticesAreAnError) {
  const auto dir = freshTempDir("loader_colours_short");
  GltfFileBuilder b;
  const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, true);
  const std::vector<float> two = {1, 1, 1, 1, 1, 1};
  const int colours = b.addAccessor(b.addView(two), kFloat, 2, "VEC3");
  b.addMeshWithNode({{"primitives", Json::array({{{"attributes", {{"POSITION", pos}, {"COLOR_0", colours}}}}})}});
  b.writeGltf(dir / "short.gltf");
  expectLoadError(dir / "short.gltf", "COLOR_0 has 2 elements, its primitive has 3 vertices");
}

TEST(GltfLoader, NonIndexedStripAndFanPrimitivesBecomeTriangleLists) {
  const auto dir = freshTempDir("loader_modes");
  GltfFileBuilder b;
  const std::vector<glm::vec3> five = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
  const int pos = b.addVec3(five, true);
  b.addMeshWithNode({{"primitives", Json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 4}},
                                                 {{"attributes", {{"POSITION", pos}}}, {"mode", 5}},
                                                 {{"attributes", {{"POSITION", pos}}}, {"mode", 6}},
                                                 {{"attributes", {{"POSITION", pos}}}, {"mode", 1}}})}});
  b.writeGltf(dir / "modes.gltf");
  const eng::Model model = loadOk(dir / "modes.gltf");
  const auto& prims = model.meshes.at(0).primitives;
  ASSERT_EQ(prims.size(), 3u) << "the LINES primitive is skipped";
  EXPECT_EQ(prims[0].indices, (std::vector<uint32_t>{0, 1, 2})) << "5 vertices: one triangle, 2 left over";
  EXPECT_EQ(prims[1].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4}));
  EXPECT_EQ(prims[2].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_TRUE(hasWarningContaining(model, "mode 1"));
  EXPECT_TRUE(hasWarningContaining(model, "not a multiple of 3"));
}

TEST(GltfLoader, GeneratesSmoothNormalsAndTheirMorphDeltasWhenNormalsAreAbsent) {
  const auto dir = freshTempDir("loader_gen_normals");
  GltfFileBuilder b = quadWithTarget();
  b.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  b.writeGlb(dir / "no_normals.glb");
  const eng::Model model = loadOk(dir / "no_normals.glb");
  const eng::Primitive& p = model.meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.normals.size(), 4u);
  for (const glm::vec3& n : p.normals) expectNear(n, {0, 0, 1});
  ASSERT_EQ(p.targets[0].normals.size(), 4u) << "lifting a corner tilts the normals, so deltas exist";
  const glm::vec3 morphed = glm::normalize(p.normals[1] + p.targets[0].normals[1]);
  EXPECT_LT(morphed.z, 0.99f);
  EXPECT_NEAR(glm::length(morphed), 1.0f, 1e-5f);
}

TEST(GltfLoader, ReadsHierarchyWithTrsAndMatrixTransforms) {
  const auto dir = freshTempDir("loader_nodes");
  GltfFileBuilder b = quadWithTarget();
  // node 0 (mesh) becomes a child of node 1 (TRS), which is a child of node 2 (matrix).
  b.doc["nodes"].push_back({{"name", "mid"}, {"children", {0}}, {"translation", {1, 2, 3}},
                            {"rotation", {0, 0.7071067811865476, 0, 0.7071067811865476}}, {"scale", {2, 2, 2}}});
  b.doc["nodes"].push_back({{"name", "top"}, {"children", {1}},
                            {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}});
  b.doc["scenes"][0]["nodes"] = {2};
  b.writeGlb(dir / "nodes.glb");
  const eng::Model model = loadOk(dir / "nodes.glb");
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.roots, std::vector<int>{2});
  EXPECT_EQ(model.nodes[0].parent, 1);
  EXPECT_EQ(model.nodes[1].parent, 2);
  EXPECT_TRUE(model.nodes[2].hasMatrix);
  EXPECT_EQ(model.nodes[1].translation, glm::vec3(1, 2, 3));
  EXPECT_EQ(model.nodes[1].scale, glm::vec3(2));
  // The quad's corner (1,0,0): scaled x2 -> (2,0,0), rotated 90 deg about +Y -> (0,0,-2),
  // translated -> (1,2,1), then the matrix adds 10 in x.
  const glm::vec3 world = glm::vec3(model.worldTransform(0) * glm::vec4(1, 0, 0, 1));
  expectNear(world, {11, 2, 1}, 1e-5f);
}

TEST(GltfLoader, DeepNodeChainLoadsWithoutRecursion) {
  const auto dir = freshTempDir("loader_deep_chain");
  GltfFileBuilder b = quadWithTarget();
  const int depth = 20000;
  // node k+1 is the parent of node k; node `depth` is the scene root.
  for (int k = 1; k <= depth; ++k) b.doc["nodes"].push_back({{"children", {k - 1}}, {"translation", {0.001, 0, 0}}});
  b.doc["scenes"][0]["nodes"] = {depth};
  b.writeGlb(dir / "chain.glb");
  const eng::Model model = loadOk(dir / "chain.glb");
  ASSERT_EQ(model.nodes.size(), static_cast<size_t>(depth) + 1);
  EXPECT_EQ(model.roots, std::vector<int>{depth});
  const eng::Aabb box = model.bounds();
  ASSERT_TRUE(box.valid());
  EXPECT_NEAR(box.min.x, depth * 0.001f, 1e-2f);
}

TEST(GltfLoader, WithoutScenesEveryParentlessNodeIsARoot) {
  const auto dir = freshTempDir("loader_no_scene");
  GltfFileBuilder b = quadWithTarget();
  b.doc.erase("scenes");
  b.doc.erase("scene");
  b.doc["nodes"].push_back({{"mesh", 0}, {"translation", {5, 0, 0}}});
  b.writeGltf(dir / "noscene.gltf");
  const eng::Model model = loadOk(dir / "noscene.gltf");
  EXPECT_EQ(model.roots, (std::vector<int>{0, 1}));
}

TEST(GltfLoader, FallsBackToTargetNWhenNamesAreMissingOrMismatched) {
  const auto dir = freshTempDir("loader_names");
  GltfFileBuilder b = quadWithTarget();
  b.doc["meshes"][0]["extras"]["targetNames"] = {"a", "b"};  // two names for one target
  b.doc["meshes"][0].erase("weights");
  b.writeGltf(dir / "names.gltf");
  const eng::Model model = loadOk(dir / "names.gltf");
  EXPECT_EQ(model.meshes.at(0).targetNames, std::vector<std::string>{"target_0"});
  EXPECT_EQ(model.meshes.at(0).defaultWeights, std::vector<float>{0.0f});
  EXPECT_TRUE(hasWarningContaining(model, "targetNames"));
}

TEST(GltfLoader, SeveralPrimitivesShareTheMeshTargets) {
  const auto dir = freshTempDir("loader_shared_targets");
  GltfFileBuilder b = quadWithTarget();
  Json second = b.doc["meshes"][0]["primitives"][0];
  b.doc["meshes"][0]["primitives"].push_back(second);
  b.writeGlb(dir / "two.glb");
  const eng::Model model = loadOk(dir / "two.glb");
  ASSERT_EQ(model.meshes.at(0).primitives.size(), 2u);
  EXPECT_EQ(model.meshes[0].targetNames.size(), 1u);
  EXPECT_EQ(model.meshes[0].primitives[1].targets.size(), 1u);
}

TEST(GltfLoader, ReadsWeightsAnimationsWithEveryInterpolation) {
  const auto dir = freshTempDir("loader_anim");
  GltfFileBuilder b = quadWithTarget();
  const int times = b.addScalars({0.0f, 0.5f, 2.0f});
  const int linear = b.addScalars({0.0f, 1.0f, 0.0f});
  const int cubic = b.addScalars({0, 0, 0, 0, 1, 0, 0, 0.5f, 0});  // in-tangent, value, out-tangent per key
  const std::vector<uint8_t> stepBytes = {0, 255, 128};              // normalized unsigned bytes
  const int step = b.addAccessor(b.addView(stepBytes), kUnsignedByte, 3, "SCALAR", true);
  const int trs = b.addAccessor(b.addView(std::vector<glm::vec3>(3, glm::vec3(0))), kFloat, 3, "VEC3");
  b.doc["animations"] = Json::array(
      {{{"name", "blink"},
        {"samplers", Json::array({{{"input", times}, {"output", linear}},
                                  {{"input", times}, {"output", cubic}, {"interpolation", "CUBICSPLINE"}},
                                  {{"input", times}, {"output", step}, {"interpolation", "STEP"}},
                                  {{"input", times}, {"output", trs}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}},
                                  {{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}},
                                  {{"sampler", 2}, {"target", {{"node", 0}, {"path", "weights"}}}},
                                  {{"sampler", 3}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  b.writeGlb(dir / "anim.glb");
  const eng::Model model = loadOk(dir / "anim.glb");
  ASSERT_EQ(model.animations.size(), 1u);
  const eng::Animation& anim = model.animations[0];
  EXPECT_EQ(anim.name, "blink");
  EXPECT_FLOAT_EQ(anim.duration(), 2.0f);
  EXPECT_EQ(anim.otherChannelCount, 1u);
  ASSERT_EQ(anim.channels.size(), 3u);
  EXPECT_EQ(anim.channels[0].interpolation, eng::Interpolation::Linear);
  EXPECT_EQ(anim.channels[0].values, (std::vector<float>{0, 1, 0}));
  EXPECT_EQ(anim.channels[0].mesh, 0);
  EXPECT_EQ(anim.channels[0].targetCount, 1u);
  EXPECT_EQ(anim.channels[1].interpolation, eng::Interpolation::CubicSpline);
  EXPECT_EQ(anim.channels[1].values.size(), 9u);
  EXPECT_EQ(anim.channels[2].interpolation, eng::Interpolation::Step);
  EXPECT_FLOAT_EQ(anim.channels[2].values[1], 1.0f);
  EXPECT_NEAR(anim.channels[2].values[2], 128.0f / 255.0f, 1e-6f);
}

TEST(GltfLoader, WeightsChannelWithWrongValueCountIsSkippedWithAWarning) {
  const auto dir = freshTempDir("loader_anim_bad");
  GltfFileBuilder b = quadWithTarget();
  const int times = b.addScalars({0.0f, 1.0f});
  const int values = b.addScalars({0.0f, 1.0f, 0.5f});
  b.doc["animations"] = Json::array({{{"samplers", Json::array({{{"input", times}, {"output", values}}})},
                                      {"channels", Json::array({{{"sampler", 0},
                                                                 {"target", {{"node", 0}, {"path", "weights"}}}}})}}});
  b.writeGlb(dir / "anim_bad.glb");
  const eng::Model model = loadOk(dir / "anim_bad.glb");
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_TRUE(model.animations[0].channels.empty());
  EXPECT_TRUE(hasWarningContaining(model, "expected 2"));
}

TEST(GltfLoader, ReadsAlphaModes) {
  const auto dir = freshTempDir("loader_alpha");
  GltfFileBuilder b = quadWithTarget();
  b.doc["materials"] = Json::array({{{"name", "skin"}},
                                    {{"name", "lashes"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.25}},
                                    {{"name", "hair"}, {"alphaMode", "MASK"}},
                                    {{"name", "highlight"}, {"alphaMode", "BLEND"}},
                                    {{"name", "odd"}, {"alphaMode", "ADDITIVE"}}});
  b.writeGlb(dir / "alpha.glb");
  const eng::Model model = loadOk(dir / "alpha.glb");
  ASSERT_EQ(model.materials.size(), 5u);
  EXPECT_EQ(model.materials[0].alphaMode, eng::AlphaMode::Opaque);
  EXPECT_EQ(model.materials[1].alphaMode, eng::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(model.materials[1].alphaCutoff, 0.25f);
  EXPECT_EQ(model.materials[2].alphaMode, eng::AlphaMode::Mask);
  EXPECT_FLOAT_EQ(model.materials[2].alphaCutoff, 0.5f) << "glTF's default cutoff";
  EXPECT_EQ(model.materials[3].alphaMode, eng::AlphaMode::Blend);
  EXPECT_EQ(model.materials[4].alphaMode, eng::AlphaMode::Opaque);
  EXPECT_TRUE(hasWarningContaining(model, "material 4 has alphaMode 'ADDITIVE'"));
}

TEST(GltfLoader, ReadsUnlitMaterials) {
  const auto dir = freshTempDir("loader_unlit");
  GltfFileBuilder b = quadWithTarget();
  b.doc["extensionsUsed"] = {"KHR_materials_unlit"};
  b.doc["extensionsRequired"] = {"KHR_materials_unlit"};
  b.doc["materials"] = Json::array({{{"name", "toon skin"}, {"extensions", {{"KHR_materials_unlit", Json::object()}}}},
                                    {{"name", "lit"}}});
  b.writeGlb(dir / "unlit.glb");
  const eng::Model model = loadOk(dir / "unlit.glb");
  ASSERT_EQ(model.materials.size(), 2u);
  EXPECT_TRUE(model.materials[0].unlit);
  EXPECT_FALSE(model.materials[1].unlit);
  EXPECT_TRUE(model.warnings.empty()) << model.warnings[0];
  const eng::ExtensionUse* record = extensionRecord(model, "KHR_materials_unlit");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome, "applied: 1 material(s) drawn unlit");
}


// One 1x1 white PNG as the file's only image (what the material tests' textures show).
void addWhiteImage(GltfFileBuilder& b) {
  auto png = eng::encodePng(1, 1, std::vector<uint8_t>(4, 255));
  ASSERT_TRUE(png.ok());
  b.doc["images"] = Json::array({{{"bufferView", b.addView(*png)}, {"mimeType", "image/png"}}});
}

TEST(GltfLoader, ReadsMtoonMaterials) {
  // VRM 1.0's extension on material 0 (its shade texture is the base colour's
  // image through another texture: exact); material 1 with MToon and unlit
  // (MToon wins); material 2 plain.
  const auto dir = freshTempDir("loader_mtoon");
  GltfFileBuilder b = quadWithTarget();
  addWhiteImage(b);
  b.doc["textures"] = Json::array({{{"source", 0}}, {{"source", 0}}});
  b.doc["extensionsUsed"] = {"VRMC_materials_mtoon", "KHR_materials_unlit"};
  b.doc["extensionsRequired"] = {"VRMC_materials_mtoon"};
  const Json mtoon = {{"specVersion", "1.0"},
                      {"shadeColorFactor", {0.3, 0.2, 0.25}},
                      {"shadeMultiplyTexture", {{"index", 1}}},
                      {"shadingShiftFactor", -0.2},
                      {"shadingToonyFactor", 0.95},
                      {"giEqualizationFactor", 0.5},
                      {"parametricRimColorFactor", {0.1, 0.1, 0.2}},
                      {"parametricRimFresnelPowerFactor", 3.0},
                      {"parametricRimLiftFactor", 0.1},
                      {"rimLightingMixFactor", 0.25},
                      {"outlineWidthMode", "screenCoordinates"},
                      {"outlineWidthFactor", 0.005},
                      {"outlineColorFactor", {0.1, 0.0, 0.0}},
                      {"outlineLightingMixFactor", 0.5},
                      {"matcapTexture", {{"index", 1}}},
                      {"matcapFactor", {0.5, 0.25, 1.0}},
                      {"shadingShiftTexture", {{"index", 1}, {"scale", 0.4}}},
                      {"rimMultiplyTexture", {{"index", 1}}},
                      {"outlineWidthMultiplyTexture", {{"index", 1}, {"texCoord", 0}}}};
  b.doc["materials"] = Json::array(
      {{{"name", "face"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
        {"extensions", {{"VRMC_materials_mtoon", mtoon}}}},
       {{"name", "hair"},
        {"extensions", {{"VRMC_materials_mtoon",
                         {{"specVersion", "1.0"}, {"shadingToonyFactor", 7}, {"uvAnimationScrollXSpeedFactor", 0.5}}},
                        {"KHR_materials_unlit", Json::object()}}}},
       {{"name", "plain"}}});
  b.writeGlb(dir / "mtoon.glb");
  const eng::Model model = loadOk(dir / "mtoon.glb");
  ASSERT_EQ(model.materials.size(), 3u);
  ASSERT_TRUE(model.materials[0].toon.has_value());
  const eng::ToonShading& face = *model.materials[0].toon;
  EXPECT_EQ(face.shadeColor, glm::vec3(0.3f, 0.2f, 0.25f));
  EXPECT_TRUE(face.shadeFromBaseTexture);
  EXPECT_FLOAT_EQ(face.shadingShift, -0.2f);
  EXPECT_FLOAT_EQ(face.shadingToony, 0.95f);
  EXPECT_FLOAT_EQ(face.giEqualization, 0.5f);
  EXPECT_EQ(face.rimColor, glm::vec3(0.1f, 0.1f, 0.2f));
  EXPECT_FLOAT_EQ(face.rimFresnelPower, 3.0f);
  EXPECT_FLOAT_EQ(face.rimLift, 0.1f);
  EXPECT_FLOAT_EQ(face.rimLightingMix, 0.25f);
  EXPECT_EQ(face.outlineMode, eng::ToonShading::OutlineWidth::Screen);
  EXPECT_FLOAT_EQ(face.outlineWidth, 0.005f);
  EXPECT_EQ(face.outlineColor, glm::vec3(0.1f, 0.0f, 0.0f));
  EXPECT_FLOAT_EQ(face.outlineLightingMix, 0.5f);
  EXPECT_EQ(face.matcapFactor, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_GE(model.materials[0].matcapImage, 0) << "the matcap texture is read";
  EXPECT_EQ(model.materials[1].matcapImage, -1);
  EXPECT_GE(model.materials[0].shadingShiftImage, 0) << "the masks are read";
  EXPECT_GE(model.materials[0].rimMultiplyImage, 0);
  EXPECT_GE(model.materials[0].outlineWidthImage, 0);
  EXPECT_FLOAT_EQ(face.shadingShiftTextureScale, 0.4f);
  EXPECT_EQ(model.materials[1].shadingShiftImage, -1);
  EXPECT_FLOAT_EQ(model.materials[1].toon->shadingShiftTextureScale, 1.0f) << "the spec's default scale";
  EXPECT_EQ(model.materials[1].toon->matcapFactor, glm::vec3(1.0f)) << "white by default";
  EXPECT_EQ(model.materials[1].toon->outlineMode, eng::ToonShading::OutlineWidth::None) << "no outline by default";
  ASSERT_TRUE(model.materials[1].toon.has_value());
  EXPECT_FLOAT_EQ(model.materials[1].toon->shadingToony, 0.9f) << "out of range: the default";
  EXPECT_EQ(model.materials[1].toon->shadeColor, glm::vec3(0.0f));
  EXPECT_FALSE(model.materials[2].toon.has_value());
  ASSERT_EQ(model.warnings.size(), 2u);
  EXPECT_EQ(model.warnings[0], "material 1 VRMC_materials_mtoon: shadingToonyFactor is not a number in [0, 1]; 0.9 used");
  EXPECT_EQ(model.warnings[1], "material 1 VRMC_materials_mtoon: its UV animation is not drawn (the textures stay still)");
  const eng::ExtensionUse* record = extensionRecord(model, "VRMC_materials_mtoon");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome.rfind("applied: 2 material(s) toon-shaded", 0), 0u) << record->outcome;
}

TEST(GltfLoader, ReadsVrm0MtoonPropertiesAsUniVrmMigratesThem) {
  // VRM 0.x: materialProperties by material index; _ShadeShift -0.2 and
  // _ShadeToony 0.8 span the 0.x range [-0.2, 0.04], so 1.0's toony is
  // (2 - 0.24) / 2 = 0.88 and its shift -(0.04 - 0.2) / 2 = 0.08. Colours
  // are sRGB-encoded; without a _ShadeTexture the shade takes _MainTex; the
  // outline width is in centimetres. The normal map (_BumpMap, by
  // _BumpScale) is drawn where the glTF material has none of its own.
  const auto dir = freshTempDir("loader_mtoon0");
  GltfFileBuilder b = quadWithTarget();
  addWhiteImage(b);
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"] = Json::array({{{"name", "face"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                    {{"name", "eyes"}},
                                    {{"name", "hair"},
                                     {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                     {"normalTexture", {{"index", 0}, {"scale", 0.8}}}}});
  b.doc["extensionsUsed"] = {"VRM"};
  b.doc["extensions"]["VRM"]["materialProperties"] = Json::array(
      {{{"name", "face"},
        {"shader", "VRM/MToon"},
        {"floatProperties",
         {{"_ShadeShift", -0.2}, {"_ShadeToony", 0.8}, {"_IndirectLightIntensity", 0.3}, {"_RimFresnelPower", 2},
          {"_OutlineWidthMode", 1}, {"_OutlineWidth", 0.2}, {"_OutlineColorMode", 0}, {"_OutlineLightingMix", 1},
          {"_BumpScale", 0.5}}},
        {"vectorProperties", {{"_ShadeColor", {0.5, 0.5, 0.5, 1}}, {"_RimColor", {0, 0, 0, 1}}}},
        {"textureProperties",
         {{"_MainTex", 0}, {"_BumpMap", 0}, {"_SphereAdd", 0}, {"_RimTexture", 0}, {"_OutlineWidthTexture", 0},
          {"_ShadingGradeTexture", 0}}}},
       {{"name", "eyes"}, {"shader", "VRM/UnlitTexture"}},
       {{"name", "hair"},
        {"shader", "VRM/MToon"},
        {"floatProperties", {{"_BumpScale", 2}}},
        {"textureProperties", {{"_MainTex", 0}, {"_BumpMap", 0}}}}});
  b.writeGlb(dir / "mtoon0.glb");
  const eng::Model model = loadOk(dir / "mtoon0.glb");
  ASSERT_EQ(model.materials.size(), 3u);
  ASSERT_TRUE(model.materials[0].toon.has_value());
  const eng::ToonShading& face = *model.materials[0].toon;
  EXPECT_GE(model.materials[0].normalImage, 0) << "_BumpMap drawn as the normal texture";
  EXPECT_FLOAT_EQ(model.materials[0].normalScale, 0.5f);
  EXPECT_GE(model.materials[2].normalImage, 0);
  EXPECT_FLOAT_EQ(model.materials[2].normalScale, 0.8f) << "the glTF material's own normalTexture wins";
  EXPECT_GE(model.materials[0].matcapImage, 0) << "_SphereAdd is the matcap";
  EXPECT_EQ(face.matcapFactor, glm::vec3(1.0f));
  EXPECT_EQ(model.materials[2].matcapImage, -1);
  EXPECT_GE(model.materials[0].rimMultiplyImage, 0) << "_RimTexture masks the rim";
  EXPECT_GE(model.materials[0].outlineWidthImage, 0) << "_OutlineWidthTexture masks the outline";
  EXPECT_EQ(model.materials[0].shadingShiftImage, -1);
  for (const std::string& warning : model.warnings) EXPECT_EQ(warning.find("_BumpMap"), std::string::npos) << warning;
  EXPECT_EQ(std::count(model.warnings.begin(), model.warnings.end(),
                       "material 0 VRM materialProperties (VRM/MToon): its _ShadingGradeTexture is not drawn (0.x's "
                       "shading grade has no 1.0 equivalent)"),
            1);
  EXPECT_NEAR(face.shadingToony, 0.88f, 1e-5f);
  EXPECT_NEAR(face.shadingShift, 0.08f, 1e-5f);
  EXPECT_NEAR(face.giEqualization, 0.7f, 1e-5f);
  EXPECT_NEAR(face.shadeColor.r, 0.2140f, 1e-3f) << "sRGB 0.5 is linear 0.214";
  EXPECT_FLOAT_EQ(face.rimFresnelPower, 2.0f);
  EXPECT_TRUE(face.shadeFromBaseTexture);
  EXPECT_EQ(face.outlineMode, eng::ToonShading::OutlineWidth::World);
  EXPECT_NEAR(face.outlineWidth, 0.002f, 1e-7f) << "0.2 cm";
  EXPECT_FLOAT_EQ(face.outlineLightingMix, 0.0f) << "fixed colour mode";
  EXPECT_FALSE(model.materials[1].toon.has_value()) << "not an MToon shader";
}

TEST(GltfLoader, ReadsTextureSamplers) {
  const auto dir = freshTempDir("loader_samplers");
  GltfFileBuilder b = quadWithTarget();
  addWhiteImage(b);
  b.doc["samplers"] = Json::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}, {"minFilter", 9728}},
                                   {{"minFilter", 9985}},
                                   {{"wrapS", 12345}, {"minFilter", 1}}});
  b.doc["textures"] = Json::array({{{"source", 0}, {"sampler", 0}},
                                   {{"source", 0}, {"sampler", 1}},
                                   {{"source", 0}},
                                   {{"source", 0}, {"sampler", 2}},
                                   {{"source", 0}, {"sampler", 7}}});
  Json materials = Json::array();
  for (int t = 0; t < 5; ++t) materials.push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", t}}}}}});
  b.doc["materials"] = materials;
  b.writeGlb(dir / "samplers.glb");
  const eng::Model model = loadOk(dir / "samplers.glb");
  ASSERT_EQ(model.materials.size(), 5u);
  using eng::TextureFilter, eng::TextureWrap;
  const eng::TextureSampling& pixelArt = model.materials[0].baseColorSampling;
  EXPECT_EQ(pixelArt.wrapS, TextureWrap::ClampToEdge);
  EXPECT_EQ(pixelArt.wrapT, TextureWrap::MirroredRepeat);
  EXPECT_EQ(pixelArt.magFilter, TextureFilter::Nearest);
  EXPECT_EQ(pixelArt.minFilter, TextureFilter::Nearest);
  EXPECT_FALSE(pixelArt.mipmaps);
  const eng::TextureSampling& mipNearest = model.materials[1].baseColorSampling;  // LINEAR_MIPMAP_NEAREST
  EXPECT_EQ(mipNearest.wrapS, TextureWrap::Repeat) << "glTF's default wrap";
  EXPECT_EQ(mipNearest.minFilter, TextureFilter::Linear);
  EXPECT_TRUE(mipNearest.mipmaps);
  EXPECT_EQ(mipNearest.mipFilter, TextureFilter::Nearest);
  EXPECT_EQ(model.materials[2].baseColorSampling, eng::TextureSampling{}) << "no sampler: repeat, trilinear";
  // Undefined codes keep their defaults and are named; a missing sampler is reported.
  EXPECT_EQ(model.materials[3].baseColorSampling, eng::TextureSampling{});
  EXPECT_TRUE(hasWarningContaining(model, "sampler 2 has wrapS 12345, minFilter 1"));
  EXPECT_EQ(model.materials[4].baseColorSampling, eng::TextureSampling{});
  EXPECT_TRUE(hasWarningContaining(model, "texture 4 refers to sampler 7, the file has 3"));
}

// The metallic-roughness texture is drawn through the base colour's UVs: one
// on another UV set, or moved by another transform, is left out with a warning.
TEST(GltfLoader, ReadsMetallicRoughnessTexturesReadThroughTheBaseColoursUvs) {
  const auto dir = freshTempDir("loader_metallic_roughness");
  GltfFileBuilder b = quadWithTarget();
  addWhiteImage(b);
  b.doc["samplers"] = Json::array({{{"wrapS", 33071}}});
  b.doc["textures"] = Json::array({{{"source", 0}}, {{"source", 0}, {"sampler", 0}}});
  const Json transform = {{"KHR_texture_transform", {{"scale", {2.0, 2.0}}}}};
  b.doc["extensionsUsed"] = Json::array({"KHR_texture_transform"});
  b.doc["materials"] = Json::array(
      {{{"name", "outfit"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}}}},
       {{"name", "no base texture"}, {"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}}}}}},
       {{"name", "other set"},
        {"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}}},
       {{"name", "other transform"},
        {"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}, {"extensions", transform}}}}}}});
  b.writeGlb(dir / "metal.glb");
  const eng::Model model = loadOk(dir / "metal.glb");
  ASSERT_EQ(model.materials.size(), 4u);
  EXPECT_EQ(model.materials[0].metallicRoughnessImage, 0);
  EXPECT_EQ(model.materials[0].metallicRoughnessSampling.wrapS, eng::TextureWrap::ClampToEdge);
  EXPECT_EQ(model.materials[0].baseColorSampling, eng::TextureSampling{});
  EXPECT_EQ(model.materials[1].metallicRoughnessImage, 0) << "TEXCOORD_0, as a material without a base texture reads";
  EXPECT_EQ(model.materials[2].metallicRoughnessImage, -1);
  EXPECT_TRUE(hasWarningContaining(model, "material 2: its metallicRoughnessTexture reads TEXCOORD_1, unlike its base colour (TEXCOORD_0)"));
  EXPECT_EQ(model.materials[3].metallicRoughnessImage, -1);
  EXPECT_TRUE(hasWarningContaining(model, "material 3: its metallicRoughnessTexture reads TEXCOORD_0 through a texture transform"));
}

// Normal and occlusion textures follow the same rule, and carry their scale
// and strength (glTF clamps the strength to 0..1).
TEST(GltfLoader, ReadsNormalAndOcclusionTexturesWithTheirScaleAndStrength) {
  const auto dir = freshTempDir("loader_normal_occlusion");
  GltfFileBuilder b = quadWithTarget();
  addWhiteImage(b);
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"] = Json::array(
      {{{"name", "skin"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
        {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
        {"occlusionTexture", {{"index", 0}, {"strength", 0.25}}}},
       {{"name", "defaults"}, {"normalTexture", {{"index", 0}}}, {"occlusionTexture", {{"index", 0}}}},
       {{"name", "occlusion on the second set"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
        {"occlusionTexture", {{"index", 0}, {"texCoord", 1}}}},
       {{"name", "strength past 1"}, {"occlusionTexture", {{"index", 0}, {"strength", 3.0}}}}});
  b.writeGlb(dir / "maps.glb");
  const eng::Model model = loadOk(dir / "maps.glb");
  ASSERT_EQ(model.materials.size(), 4u);
  EXPECT_EQ(model.materials[0].normalImage, 0);
  EXPECT_FLOAT_EQ(model.materials[0].normalScale, 0.5f);
  EXPECT_EQ(model.materials[0].occlusionImage, 0);
  EXPECT_FLOAT_EQ(model.materials[0].occlusionStrength, 0.25f);
  EXPECT_EQ(model.materials[1].normalImage, 0);
  EXPECT_FLOAT_EQ(model.materials[1].normalScale, 1.0f);
  EXPECT_FLOAT_EQ(model.materials[1].occlusionStrength, 1.0f);
  EXPECT_EQ(model.materials[2].occlusionImage, -1);
  EXPECT_TRUE(hasWarningContaining(model, "material 2: its occlusionTexture reads TEXCOORD_1, unlike its base colour (TEXCOORD_0)"));
  EXPECT_FLOAT_EQ(model.materials[3].occlusionStrength, 1.0f) << "glTF's range is 0..1";
}

TEST(GltfLoader, ReadsMaterialFactorsTextureAndDetailLayers) {
  const auto dir = freshTempDir("loader_material");
  GltfFileBuilder b = quadWithTarget();
  const std::vector<uint8_t> pixels = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
  auto png = eng::encodePng(2, 2, pixels);
  ASSERT_TRUE(png.ok());
  // The detail layer's image differs: images with the same bytes share one decode.
  const std::vector<uint8_t> detailPixels(pixels.rbegin(), pixels.rend());
  auto detailPng = eng::encodePng(2, 2, detailPixels);
  ASSERT_TRUE(detailPng.ok());
  b.doc["images"] = Json::array({{{"bufferView", b.addView(*png)}, {"mimeType", "image/png"}, {"name", "checker"}},
                                 {{"uri", "data:image/png;base64," + scene_test::base64(*detailPng)}}});
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"] = Json::array({{{"name", "skin"},
                                     {"doubleSided", true},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}},
                                                               {"baseColorTexture", {{"index", 0}}},
                                                               {"roughnessFactor", 0.3},
                                                               {"metallicFactor", 0.1}}},
                                     {"extras", {{"detailLayers", Json::array({{{"image", 1}, {"target", "lift"},
                                                                                {"strength", 0.75}},
                                                                               {{"image", 1}, {"target", "crease"},
                                                                                {"blend", "modulate"}},
                                                                               {{"image", 1}, {"target", "odd"},
                                                                                {"blend", "screen"}}})}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.writeGlb(dir / "material.glb");
  const eng::Model model = loadOk(dir / "material.glb");
  ASSERT_EQ(model.images.size(), 2u);
  EXPECT_EQ(model.images[0].width, 2);
  EXPECT_EQ(model.images[0].rgba8, pixels);
  EXPECT_EQ(model.images[1].rgba8, detailPixels) << "data: URI image";
  ASSERT_EQ(model.materials.size(), 1u);
  const eng::Material& m = model.materials[0];
  EXPECT_EQ(m.name, "skin");
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1));
  EXPECT_EQ(m.baseColorImage, 0);
  EXPECT_FLOAT_EQ(m.roughness, 0.3f);
  EXPECT_FLOAT_EQ(m.metallic, 0.1f);
  ASSERT_EQ(m.detailLayers.size(), 2u) << "the layer with an unknown blend is left out";
  EXPECT_EQ(m.detailLayers[0].image, 1);
  EXPECT_EQ(m.detailLayers[0].target, "lift");
  EXPECT_FLOAT_EQ(m.detailLayers[0].strength, 0.75f);
  EXPECT_EQ(m.detailLayers[0].blend, eng::DetailBlend::Mix);
  EXPECT_EQ(m.detailLayers[1].target, "crease");
  EXPECT_EQ(m.detailLayers[1].blend, eng::DetailBlend::Modulate);
  EXPECT_TRUE(hasWarningContaining(model, "detail layer 2 has blend 'screen' (known: 'mix', 'modulate'); ignored"));
  EXPECT_EQ(model.meshes[0].primitives[0].material, 0);
}

// Emission is the factor times the emissive texture. A texture that cannot
// be drawn (another UV set) takes the factor with it: alone, the factor would
// light the whole surface.
TEST(GltfLoader, ReadsEmissiveFactorsAndTexturesAndLeavesOutEmissionItCannotMask) {
  const auto dir = freshTempDir("loader_emissive");
  GltfFileBuilder b = quadWithTarget();
  const std::vector<uint8_t> pixels = {255, 255, 255, 255};
  auto png = eng::encodePng(1, 1, pixels);
  ASSERT_TRUE(png.ok());
  b.doc["images"] = Json::array({{{"bufferView", b.addView(*png)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"] = Json::array({{{"name", "glow"}, {"emissiveFactor", {0.5, 0.25, 0}}},
                                    {{"name", "masked"}, {"emissiveFactor", {1, 1, 1}},
                                     {"emissiveTexture", {{"index", 0}}}},
                                    {{"name", "dark"}, {"emissiveTexture", {{"index", 0}}}},
                                    {{"name", "masked on the second set"}, {"emissiveFactor", {1, 1, 1}},
                                     {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.writeGlb(dir / "emissive.glb");
  const eng::Model model = loadOk(dir / "emissive.glb");
  ASSERT_EQ(model.materials.size(), 4u);
  EXPECT_EQ(model.materials[0].emissiveFactor, glm::vec3(0.5f, 0.25f, 0.0f));
  EXPECT_EQ(model.materials[0].emissiveImage, -1);
  EXPECT_EQ(model.materials[1].emissiveFactor, glm::vec3(1.0f));
  EXPECT_EQ(model.materials[1].emissiveImage, 0);
  EXPECT_EQ(model.materials[2].emissiveFactor, glm::vec3(0.0f));
  EXPECT_EQ(model.materials[2].emissiveImage, -1) << "no emission for the texture to mask";
  EXPECT_FALSE(hasWarningContaining(model, "material 2")) << "nothing to leave out";
  EXPECT_EQ(model.materials[3].emissiveFactor, glm::vec3(0.0f));
  EXPECT_EQ(model.materials[3].emissiveImage, -1);
  EXPECT_TRUE(hasWarningContaining(model, "material 3: its emissiveFactor is left out with its emissiveTexture"));
}

TEST(GltfLoader, BrokenImageIsSkippedWithAWarningAndTheMaterialLosesItsTexture) {
  const auto dir = freshTempDir("loader_broken_image");
  GltfFileBuilder b = quadWithTarget();
  const std::vector<uint8_t> junk = {0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5, 6, 7, 8};
  b.doc["images"] = Json::array({{{"bufferView", b.addView(junk)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.writeGlb(dir / "broken_image.glb");
  const eng::Model model = loadOk(dir / "broken_image.glb");
  EXPECT_TRUE(model.images.empty());
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.materials[0].baseColorImage, -1);
  EXPECT_TRUE(hasWarningContaining(model, "image 0 skipped"));
}

TEST(GltfLoader, OptionalUnknownExtensionIsIgnoredWithAWarning) {
  const auto dir = freshTempDir("loader_optional_ext");
  GltfFileBuilder b = quadWithTarget();
  b.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  b.writeGltf(dir / "optional.gltf");
  const eng::Model model = loadOk(dir / "optional.gltf");
  EXPECT_TRUE(hasWarningContaining(model, "optional extension KHR_materials_sheen ignored"));
  const eng::ExtensionUse* record = extensionRecord(model, "KHR_materials_sheen");
  ASSERT_NE(record, nullptr);
  EXPECT_FALSE(record->required);
  EXPECT_EQ(record->outcome.rfind("ignored", 0), 0u) << record->outcome;
}

TEST(GltfLoader, DetectsGlbByContentWhateverTheExtension) {
  const auto dir = freshTempDir("loader_detect");
  quadWithTarget().writeGlb(dir / "really_binary.gltf");
  const eng::Model model = loadOk(dir / "really_binary.gltf");
  EXPECT_EQ(model.meshes.size(), 1u);
}

TEST(GltfLoader, UriWithShellCharactersIsAPlainFileName) {
  // A file really named like a shell expansion is read as is, never expanded.
  const auto dir = freshTempDir("loader_literal_uri");
  quadWithTarget().writeGltf(dir / "literal.gltf", "$(echo x) `y` ~z*.bin");
  const eng::Model model = loadOk(dir / "literal.gltf");
  EXPECT_EQ(model.meshes.size(), 1u);
}

}  // namespace
