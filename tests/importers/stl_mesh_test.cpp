// Reading STL scans (importers/stl_mesh.h): binary (whatever its header says)
// and ASCII, corners welded into one surface, and refusal of broken files
// with one line naming the file.
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "importers/load_face.h"
#include "tests/common/obj_test_files.h"
#include "tests/common/test_support.h"

// Named, so that its helpers do not meet other files' in a unity build.
namespace stl_mesh_test {
namespace {

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

std::string outcomeOf(const std::string& bytes, const std::string& name = "broken.stl") {
  auto face = importers::loadFaceFromBytes(bytesOf(bytes), name);
  return face ? std::string("loaded") : face.error().message;
}

// A unit cube: 12 facets over 8 corners.
std::string asciiCube() {
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  auto corner = [](int i) { return std::to_string(i & 1) + " " + std::to_string((i >> 1) & 1) + " " + std::to_string((i >> 2) & 1); };
  std::string text = "solid cube\n";
  for (const auto& q : quads)
    for (const std::array<int, 3>& tri : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      text += "  facet normal 0 0 0\n    outer loop\n";
      for (int c : tri) text += "      vertex " + corner(c) + "\n";
      text += "    endloop\n  endfacet\n";
    }
  return text + "endsolid cube\n";
}

TEST(StlMesh, AnAsciiCubeIsWeldedIntoOneSurface) {
  auto face = importers::loadFaceFromBytes(bytesOf(asciiCube()), "cube.stl");
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->format, importers::FaceFormat::Stl);
  EXPECT_TRUE(importers::isPlainMesh(face->format)) << "autorig rigs it";
  ASSERT_EQ(face->model.meshes.size(), 1u);
  const eng::Primitive& p = face->model.meshes[0].primitives.at(0);
  EXPECT_EQ(p.positions.size(), 8u) << "36 corners at 8 positions";
  EXPECT_EQ(p.indices.size(), 36u);
  for (size_t v = 0; v < p.positions.size(); ++v)
    EXPECT_GT(glm::dot(p.normals[v], glm::normalize(p.positions[v] - glm::vec3(0.5f))), 0.5f) << "smooth normals point out";
}

TEST(StlMesh, TheHeadAsABinaryStlIsTheSameSurface) {
  auto head = importers::loadFace(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(head) << head.error().message;
  // Exporters often begin a binary file's header with "solid": the sizes tell it apart.
  for (const char* header : {"binary STL written by the tests", "solid head exported by a scanner"}) {
    auto stl = importers::loadFaceFromBytes(bytesOf(testing_support::modelAsStl(head->model, header)), "head.stl");
    ASSERT_TRUE(stl) << header << ": " << stl.error().message;
    EXPECT_EQ(stl->format, importers::FaceFormat::Stl);
    const eng::Aabb a = head->model.bounds(), b = stl->model.bounds();
    EXPECT_LT(glm::distance(a.min, b.min) + glm::distance(a.max, b.max), 1e-6f);
    size_t triangles = 0;
    for (const eng::Mesh& m : head->model.meshes)
      for (const eng::Primitive& p : m.primitives) triangles += p.indices.size() / 3;
    EXPECT_EQ(stl->model.meshes[0].primitives[0].indices.size() / 3, triangles);
    EXPECT_LT(stl->model.totalVertexCount(), head->model.totalVertexCount()) << "welded where the head's seams split vertices";
  }
}

TEST(StlMeshValidity, BrokenFilesAreOneLineNamingTheFile) {
  auto head = importers::loadFace(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(head) << head.error().message;
  std::string nanCorner = testing_support::modelAsStl(head->model);
  const float nan = std::nanf("");
  std::memcpy(&nanCorner[84 + 50 * 7 + 16], &nan, 4);  // triangle 7's first corner's y
  struct Case {
    const char* what;
    std::string bytes;
    const char* says;
  };
  const Case cases[] = {
      {"a NaN corner", nanCorner, "triangle 7 has a corner that is not a finite number"},
      {"a vertex outside a facet", "solid x\nvertex 0 0 0\nfacet normal 0 0 1\n", "line 2: a vertex outside any facet"},
      {"a vertex without numbers", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 zero 0\n", "line 4: 'vertex 0 zero 0' is not 'vertex' and three finite numbers"},
      {"a word that is no statement", "solid x\nfacet normal 0 0 1\nouter loop\nvortex 0 0 0\n", "line 4: 'vortex 0 0 0' is no STL statement"},
      {"a file cut short", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "the last facet has no 'endfacet'"},
      {"no triangles", "solid x\nfacet normal 0 0 1\nouter loop\nendloop\nendfacet\nendsolid\n", "no triangles"},
  };
  for (const Case& c : cases) {
    const std::string said = outcomeOf(c.bytes);
    EXPECT_EQ(said.find('\n'), std::string::npos) << c.what << ": " << said;
    EXPECT_EQ(said.rfind("broken.stl: ", 0), 0u) << c.what << ": " << said;
    EXPECT_NE(said.find(c.says), std::string::npos) << c.what << ": " << said;
  }
}

}  // namespace
}  // namespace stl_mesh_test
