// Broken skins: data that cannot be read (wrong component types, NaN
// weights, wrong counts) is one error naming the file; a skin that cannot be
// used (bad joint nodes, too few or non-finite inverse bind matrices, a
// vertex naming a joint the skin lacks) is dropped with a warning and the
// mesh is drawn unskinned, as Filament does.
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"
#include "tests/engine/scene/skin_test_files.h"

namespace {

using namespace scene_test;
using testing_support::freshTempDir;

std::filesystem::path write(const GltfFileBuilder& b, const std::string& name) {
  const auto dir = freshTempDir("skin_bad_" + name);
  b.writeGlb(dir / (name + ".glb"));
  return dir / (name + ".glb");
}

// Loads, expects a warning containing `problem`, and that the mesh node lost its skin.
void expectSkinDropped(const std::filesystem::path& path, const std::string& problem) {
  auto model = eng::loadModel(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  bool warned = false;
  for (const std::string& w : model->warnings) warned = warned || w.find(problem) != std::string::npos;
  EXPECT_TRUE(warned) << "no warning with '" << problem << "'";
  ASSERT_FALSE(model->nodes.empty());
  EXPECT_EQ(model->nodes[0].skin, -1);
  EXPECT_FALSE(model->meshes.at(0).primitives.at(0).joints.empty()) << "the influences stay; only the skin is unused";
}

// Index of the first accessor with this attribute on primitive 0.
int attributeAccessor(const GltfFileBuilder& b, const std::string& attribute) {
  return b.doc["meshes"][0]["primitives"][0]["attributes"][attribute].get<int>();
}

// Overwrites float `index` of accessor `accessor`'s data.
void poke(GltfFileBuilder& b, int accessor, size_t index, float value) {
  const int view = b.doc["accessors"][accessor]["bufferView"].get<int>();
  const size_t offset = b.doc["bufferViews"][view]["byteOffset"].get<size_t>();
  std::memcpy(b.bin.data() + offset + index * sizeof(float), &value, sizeof(float));
}

int inverseBindAccessor(const GltfFileBuilder& b) { return b.doc["skins"][0]["inverseBindMatrices"].get<int>(); }

TEST(SkinningBadInput, VertexNamesAJointTheSkinLacks) {
  GltfFileBuilder b = skinnedStrip({.jointType = kUnsignedShort});
  b.doc["skins"][0]["joints"] = {1};  // one joint; the strip uses joints 0 and 1
  b.doc["skins"][0].erase("inverseBindMatrices");
  expectSkinDropped(write(b, "joint_range"), "uses joint 1, the skin has 1");
}

TEST(SkinningBadInput, TooFewInverseBindMatrices) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["accessors"][inverseBindAccessor(b)]["count"] = 1;
  expectSkinDropped(write(b, "ibm_count"), "has 1 inverse bind matrices for 2 joints");
}

TEST(SkinningBadInput, NanInverseBindMatrix) {
  GltfFileBuilder b = skinnedStrip();
  poke(b, inverseBindAccessor(b), 20, std::numeric_limits<float>::quiet_NaN());
  expectSkinDropped(write(b, "ibm_nan"), "NaN");
}

TEST(SkinningBadInput, JointThatIsNoNode) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["skins"][0]["joints"] = {1, 9};
  expectSkinDropped(write(b, "joint_node"), "joint node 9 does not exist");
}

TEST(SkinningBadInput, NodeNamesASkinThatDoesNotExist) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["nodes"][0]["skin"] = 4;
  expectSkinDropped(write(b, "node_skin"), "refers to skin 4, the file has 1");
}

TEST(SkinningBadInput, FloatJointIndices) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["accessors"][attributeAccessor(b, "JOINTS_0")]["componentType"] = kFloat;
  expectLoadError(write(b, "float_joints"), "JOINTS_0 has componentType 5126");
}

TEST(SkinningBadInput, WeightsNotNormalized) {
  GltfFileBuilder b = skinnedStrip({.weightType = kUnsignedByte});
  b.doc["accessors"][attributeAccessor(b, "WEIGHTS_0")].erase("normalized");
  expectLoadError(write(b, "weights_unnormalized"), "(not normalized)");
}

TEST(SkinningBadInput, NanWeight) {
  GltfFileBuilder b = skinnedStrip();
  poke(b, attributeAccessor(b, "WEIGHTS_0"), 5, std::numeric_limits<float>::quiet_NaN());
  expectLoadError(write(b, "weights_nan"), "WEIGHTS_0): element 1 is NaN");
}

TEST(SkinningBadInput, JointCountDiffersFromVertexCount) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["accessors"][attributeAccessor(b, "JOINTS_0")]["count"] = 5;
  expectLoadError(write(b, "joint_count"), "JOINTS_0 / WEIGHTS_0 have 5 / 6 elements, its primitive has 6 vertices");
}

TEST(SkinningBadInput, JointsWithoutWeightsAreIgnoredWithAWarning) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
  auto model = eng::loadModel(write(b, "joints_alone"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->meshes[0].primitives[0].joints.empty());
  ASSERT_FALSE(model->warnings.empty());
  EXPECT_NE(model->warnings[0].find("JOINTS_0 without its pair"), std::string::npos) << model->warnings[0];
}

TEST(SkinningBadInput, RotationChannelOfTheWrongType) {
  GltfFileBuilder b = skinnedStrip();
  const int output = b.doc["animations"][0]["samplers"][0]["output"].get<int>();
  b.doc["accessors"][output]["type"] = "VEC3";
  expectLoadError(write(b, "rotation_vec3"), "has type VEC3, expected VEC4");
}

TEST(SkinningBadInput, ChannelOnAMatrixNodeIsSkipped) {
  GltfFileBuilder b = skinnedStrip();
  b.doc["nodes"][2].erase("translation");
  b.doc["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1};
  auto model = eng::loadModel(write(b, "matrix_node"));
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->animations.at(0).nodeChannels.empty());
  EXPECT_EQ(model->nodes[0].skin, 0) << "the skin itself is fine";
  bool warned = false;
  for (const std::string& w : model->warnings) warned = warned || w.find("which has a matrix") != std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
