// The one loader of every program (importers/load_face.h): formats told
// apart by content, each file read once, shapes baked into the rest mesh,
// and the display dressing only when asked for.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_writer.h"
#include "importers/load_face.h"
#include "tests/common/obj_test_files.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace {

using cli_test::kCustom;
using cli_test::makeTestFace;

// The test face as an untextured scan arrives: one plain white material.
std::filesystem::path writePlasterFace(const std::string& name) {
  eng::Model face = makeTestFace();
  for (eng::Material& material : face.materials) material.baseColorFactor = glm::vec4(1.0f);
  const std::filesystem::path path = testing_support::freshTempDir(name) / "plaster.glb";
  EXPECT_TRUE(eng::saveModel(face, path));
  return path;
}

TEST(LoadFace, ShapesBakeIntoTheRestMesh) {
  eng::Model model = makeTestFace();
  const eng::Model original = model;
  const std::vector<std::string> shapes = {"Custom-Shape=0.5"};  // loose spelling of "custom_shape"
  ASSERT_TRUE(importers::bakeShapes(model, shapes));
  const eng::Primitive& before = original.meshes[0].primitives[0];
  const eng::Primitive& after = model.meshes[0].primitives[0];
  const auto& delta = before.targets[kCustom].positions;
  bool moved = false;
  for (size_t v = 0; v < before.positions.size(); ++v) {
    EXPECT_NEAR(after.positions[v].z, before.positions[v].z + 0.5f * delta[v].z, 1e-6f);
    moved |= delta[v] != glm::vec3(0.0f);
  }
  EXPECT_TRUE(moved);
  EXPECT_EQ(model.meshes[0].defaultWeights[kCustom], 0.0f);  // not applied twice
}

// The bytes that told the format apart are the ones parsed: the file is not
// opened again (here it is gone before the load).
TEST(LoadFace, ParsesTheBytesItWasGivenWithoutReopeningTheFile) {
  const std::filesystem::path path = cli_test::writeTestFace("load_face_bytes");
  auto fromFile = importers::loadFace(path);
  ASSERT_TRUE(fromFile) << fromFile.error().message;
  auto bytes = eng::readFileBytes(path, size_t{1} << 24);
  ASSERT_TRUE(bytes) << bytes.error().message;
  std::filesystem::remove(path);
  auto fromBytes = importers::loadFaceFromBytes(*bytes, path);
  ASSERT_TRUE(fromBytes) << fromBytes.error().message;
  EXPECT_EQ(fromBytes->format, importers::FaceFormat::Gltf);
  EXPECT_EQ(fromBytes->model.meshes[0].targetNames, fromFile->model.meshes[0].targetNames);
  EXPECT_EQ(fromBytes->model.meshes[0].primitives[0].positions, fromFile->model.meshes[0].primitives[0].positions);
  EXPECT_EQ(importers::loadFace(path).error().kind, eng::ErrorKind::NotFound) << "the file is really gone";
}

TEST(LoadFaceValidity, BytesOfNoFaceFormatAreNamed) {
  // A 3MF (a zip archive), and an STL-like text with no facet in it.
  for (const auto& [text, name] : {std::pair<std::string, std::string>{std::string("PK\x03\x04\x14\0\0\0", 8), "cube.3mf"},
                                   {"solid cube\nendsolid\n", "cube.stl"}}) {
    const std::vector<uint8_t> bytes(text.begin(), text.end());
    auto face = importers::loadFaceFromBytes(bytes, name);
    ASSERT_FALSE(face) << name;
    EXPECT_EQ(face.error().kind, eng::ErrorKind::Unsupported) << name;
    EXPECT_NE(face.error().message.find(name + ": not a face this program reads"), std::string::npos) << face.error().message;
  }
}

// One OBJ file is a face without targets (a scan, a sculpt): told by its
// first statement, past an exporter's comment lines longer than the bytes
// that tell the other formats apart, whatever its name.
TEST(LoadFace, OneObjFileIsAFaceWithoutTargets) {
  const eng::Model face = makeTestFace();
  const std::string header = "# Exported by a scanner's own software, version 12.3.4 (a long comment line)\n#\n\n";
  const std::filesystem::path path = testing_support::freshTempDir("load_face_obj") / "scan.dat";
  testing_support::writeFile(path, testing_support::modelAsObj(face, header));
  auto loaded = importers::loadFace(path);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->format, importers::FaceFormat::Obj);
  EXPECT_EQ(loaded->model.sourcePath, path.string());
  size_t vertices = 0, targets = 0;
  for (const eng::Mesh& mesh : loaded->model.meshes)
    for (const eng::Primitive& p : mesh.primitives) vertices += p.positions.size(), targets += p.targets.size();
  EXPECT_EQ(vertices, face.totalVertexCount());
  EXPECT_EQ(targets, 0u);
  // The bytes given are the ones parsed: the path only names the file (and places its .mtl).
  const std::string text = testing_support::modelAsObj(face, header);
  auto fromBytes = importers::loadFaceFromBytes(std::vector<uint8_t>(text.begin(), text.end()),
                                                path.parent_path() / "not-on-disk.obj");
  ASSERT_TRUE(fromBytes) << fromBytes.error().message;
  EXPECT_EQ(fromBytes->model.totalVertexCount(), loaded->model.totalVertexCount());
}

TEST(LoadFaceValidity, TextThatIsNoObjIsNamed) {
  const std::string text = "# a comment\nsolid cube\nv 0 0 0\n";
  const std::vector<uint8_t> bytes(text.begin(), text.end());
  auto face = importers::loadFaceFromBytes(bytes, "cube.txt");
  ASSERT_FALSE(face);
  EXPECT_NE(face.error().message.find("cube.txt: not a face this program reads"), std::string::npos) << face.error().message;
}

TEST(LoadFace, DressingIsOffUnlessAskedFor) {
  const std::filesystem::path path = writePlasterFace("load_face_plain");
  auto face = importers::loadFace(path);
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_FALSE(face->dressed.has_value());
  EXPECT_EQ(&face->displayModel(), &face->model);
}

// Asked for, the display gets a dressed copy (skin tone, occlusion) and the
// model stays as the file has it: what tools inspect and export.
TEST(LoadFace, DressingForDisplayLeavesTheModelAsLoaded) {
  const std::filesystem::path path = writePlasterFace("load_face_dressed");
  auto plain = importers::loadFace(path);
  auto face = importers::loadFace(path, {.dressForDisplay = true});
  ASSERT_TRUE(plain && face);
  ASSERT_TRUE(face->dressed.has_value());
  EXPECT_EQ(&face->displayModel(), &*face->dressed);
  EXPECT_EQ(face->model.materials.size(), plain->model.materials.size());
  EXPECT_EQ(face->model.materials[0].baseColorFactor, glm::vec4(1.0f));
  EXPECT_TRUE(face->model.meshes[0].primitives[0].colors.empty());
  const eng::Model& dressed = *face->dressed;
  EXPECT_GT(dressed.materials.size(), face->model.materials.size()) << "the skin tone is a material of its own";
  const eng::Primitive& skin = dressed.meshes[0].primitives[0];
  EXPECT_LT(dressed.materials[size_t(skin.material)].baseColorFactor.r, 0.99f);
  EXPECT_EQ(skin.colors.size(), skin.positions.size()) << "occlusion baked into the vertex colours";
  EXPECT_EQ(skin.positions, face->model.meshes[0].primitives[0].positions) << "the same geometry";
}

}  // namespace
