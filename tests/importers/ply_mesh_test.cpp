// Reading PLY scans (importers/ply_mesh.h): ASCII and binary,
// vertex colours, texture coordinates and MeshLab's texture comment, and
// refusal of broken files with one line naming the file.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/uv_raster.h"
#include "engine/scene/image_io.h"
#include "importers/load_face.h"
#include "importers/ply_mesh.h"
#include "tests/common/test_support.h"

namespace {

using testing_support::freshTempDir;
using testing_support::writeFile;

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

// What loading `bytes` as the file `name` says: the error, or "loaded".
std::string refusalOf(const std::string& bytes, const std::string& name) {
  auto face = importers::loadFaceFromBytes(bytesOf(bytes), name);
  return face ? std::string("loaded") : face.error().message;
}

// A unit square (a quad) and a triangle beside it, painted per vertex as MeshLab writes it.
const std::string kPaintedAscii =
    "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 255 128 0\n1 0 0 0 0 0\n1 1 0 51 51 51\n0 1 0 255 255 255\n2 0 0 10 20 30\n"
    "4 0 1 2 3\n3 1 4 2\n";

TEST(PlyMesh, AsciiFacesAndVertexColoursBecomeAFaceWithoutTargets) {
  const auto dir = freshTempDir("ply_ascii");
  writeFile(dir / "scan.ply", kPaintedAscii);
  auto face = importers::loadFace(dir / "scan.ply");
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->format, importers::FaceFormat::Ply);
  EXPECT_TRUE(importers::isPlainMesh(face->format)) << "autorig rigs it";
  ASSERT_EQ(face->model.meshes.size(), 1u);
  const eng::Primitive& p = face->model.meshes[0].primitives.at(0);
  EXPECT_EQ(p.positions.size(), 5u) << "the file's vertices, shared by its faces";
  EXPECT_EQ(p.indices.size(), 9u) << "the quad as two triangles and the triangle";
  EXPECT_TRUE(p.targets.empty());
  ASSERT_EQ(p.colors.size(), 5u);
  for (size_t v = 0; v < p.positions.size(); ++v) {
    if (p.positions[v] == glm::vec3(0, 0, 0)) {
      EXPECT_NEAR(p.colors[v].r, 1.0f, 1e-5f);
      EXPECT_NEAR(p.colors[v].g, eng::srgbToLinear(128.0f / 255.0f), 1e-3f) << "display values made linear";
    }
    if (p.positions[v] == glm::vec3(1, 1, 0)) {
      EXPECT_NEAR(p.colors[v].b, eng::srgbToLinear(0.2f), 1e-3f);
    }
  }
  EXPECT_EQ(p.normals.size(), p.positions.size()) << "smooth normals made where the file has none";
}

// Binary little-endian, as scanners write it, with texture coordinates and
// the texture MeshLab names in a comment (found beside the file).
TEST(PlyMesh, BinaryWithTextureCoordinatesAndItsTextureFile) {
  const auto dir = freshTempDir("ply_binary");
  const std::vector<uint8_t> skin = {200, 150, 120, 255, 200, 150, 120, 255, 200, 150, 120, 255, 200, 150, 120, 255};
  ASSERT_TRUE(eng::writePng(dir / "skin.png", 2, 2, skin));
  std::string file =
      "ply\nformat binary_little_endian 1.0\ncomment TextureFile skin.png\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float vertices[3][5] = {{0, 0, 0, 0, 0}, {1, 0, 0, 1, 0}, {0, 1, 0, 0, 1}};
  file.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
  const uint8_t corners = 3;
  const int32_t indices[3] = {0, 1, 2};
  file.append(reinterpret_cast<const char*>(&corners), 1);
  file.append(reinterpret_cast<const char*>(indices), sizeof indices);
  writeFile(dir / "textured.ply", file);

  auto face = importers::loadFace(dir / "textured.ply");
  ASSERT_TRUE(face) << face.error().message;
  const eng::Primitive& p = face->model.meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.positions.size(), 3u);
  ASSERT_EQ(p.texcoords.size(), 3u);
  for (size_t v = 0; v < 3; ++v) {
    if (p.positions[v] == glm::vec3(0, 1, 0)) {
      EXPECT_EQ(p.texcoords[v], glm::vec2(0, 0)) << "PLY's t points up, glTF's v down";
    }
  }
  ASSERT_GE(p.material, 0);
  const eng::Material& material = face->model.materials.at(size_t(p.material));
  ASSERT_GE(material.baseColorImage, 0) << "skin.png, named by the comment";
  EXPECT_EQ(face->model.images.at(size_t(material.baseColorImage)).width, 2);
}

// MeshLab writes a textured scan's UVs per face corner ("texcoord" lists): the
// corners of a vertex with the same UV are one vertex again (the surface
// stays joined), those across a seam two.
TEST(PlyMesh, PerCornerTexcoordsJoinWhereTheyAgreeAndSplitAtSeams) {
  const std::string quad =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "3 0 1 2 6 0 0 0.5 0 0.5 0.5\n"
      "3 0 2 3 6 0 0 0.5 0.5 0.9 0.9\n";  // vertex 3's UV is its own; vertex 0's and 2's agree
  auto face = importers::loadFaceFromBytes(bytesOf(quad), "quad.ply");
  ASSERT_TRUE(face) << face.error().message;
  const eng::Primitive& p = face->model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(p.positions.size(), 4u) << "the two triangles share their diagonal";
  ASSERT_EQ(p.texcoords.size(), 4u);
  for (size_t v = 0; v < 4; ++v) {
    if (p.positions[v] == glm::vec3(1, 1, 0)) {
      EXPECT_EQ(p.texcoords[v], glm::vec2(0.5f, 0.5f));
    }
    if (p.positions[v] == glm::vec3(0, 1, 0)) {
      EXPECT_NEAR(p.texcoords[v].y, 0.1f, 1e-6f) << "t 0.9 up is v 0.1 down";
    }
  }
  const std::string seam = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n"
                           "end_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2 6 0 0 1 0 1 1\n3 0 2 1 6 0.5 0 1 1 1 0\n";
  auto split = importers::loadFaceFromBytes(bytesOf(seam), "seam.ply");
  ASSERT_TRUE(split) << split.error().message;
  EXPECT_EQ(split->model.meshes.at(0).primitives.at(0).positions.size(), 4u) << "vertex 0 on both sides of a seam";
}

TEST(PlyMeshValidity, BrokenFilesAreOneLineNamingTheFile) {
  const std::string vertices3 = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string oneFace = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  struct Case {
    std::string name, bytes, says;
  };
  std::string binaryNan = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\n" + oneFace;
  const float corners[9] = {0, 0, 0, 1, 0, std::nanf(""), 0, 1, 0};
  const int32_t triangle[3] = {0, 1, 2};
  binaryNan.append(reinterpret_cast<const char*>(corners), sizeof corners);
  binaryNan.push_back('\3');
  binaryNan.append(reinterpret_cast<const char*>(triangle), sizeof triangle);
  const Case cases[] = {
      // Cut short: the header promises three vertices and a face the bytes do not hold.
      {"cut.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" +
           oneFace + "\1\2",
       "cut.ply: element 'vertex' claims 3 records of 3 values; the file has 2 bytes"},
      // A header claiming more than the bytes can hold is refused by its sizes, before anything is read for it.
      {"huge.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n0123456789ab",
       "huge.ply: element 'vertex' claims 4000000000 records of 3 values; the file has 12 bytes after its header"},
      {"bare.ply", "ply\nelement vertex 0\nend_header\n", "bare.ply: no 'format' line"},
      // A point cloud: a face needs a surface.
      {"cloud.ply", vertices3 + "end_header\n0 0 0\n1 0 0\n0 1 0\n",
       "cloud.ply: no faces (a point cloud: a face needs a surface)"},
      // Not a number, in either kind of file.
      {"nan.ply", vertices3 + oneFace + "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", "nan.ply: line 11: 'nan' is not a finite number"},
      {"nan_binary.ply", binaryNan, "nan_binary.ply: vertex 1 is not finite"},
      // A face naming a vertex the file does not have.
      {"beyond.ply", vertices3 + oneFace + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "beyond.ply: face 0 names vertex 7"},
  };
  for (const Case& c : cases) {
    const std::string said = refusalOf(c.bytes, c.name);
    EXPECT_NE(said.find(c.says), std::string::npos) << c.name << ": " << said;
    EXPECT_EQ(said.find('\n'), std::string::npos) << said;
  }
}

TEST(PlyMeshValidity, ATextureOutsideTheFilesFolderIsAWarning) {
  const auto dir = freshTempDir("ply_outside");
  std::string text = kPaintedAscii;
  text.replace(text.find("comment made by hand"), std::strlen("comment made by hand"), "comment TextureFile ../../secret.png");
  writeFile(dir / "scan.ply", text);
  auto mesh = importers::readPlyPolygonMesh(bytesOf(text), dir / "scan.ply");
  ASSERT_TRUE(mesh) << mesh.error().message;
  ASSERT_EQ(mesh->warnings.size(), 1u);
  EXPECT_NE(mesh->warnings[0].find("'../../secret.png' is outside the PLY's folder"), std::string::npos) << mesh->warnings[0];
  for (const importers::ObjMaterial& m : mesh->materials) EXPECT_TRUE(m.diffuseTexture.empty());
}

}  // namespace
