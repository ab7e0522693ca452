// Reading OBJ polygons: corners, faces, materials, and refusal of broken files.
#include <gtest/gtest.h>

#include "importers/obj_mesh.h"
#include "tests/common/test_support.h"

namespace {

using testing_support::freshTempDir;
using testing_support::writeFile;

TEST(ObjMesh, KeepsPolygonsAndSeparateIndexStreams) {
  const auto dir = freshTempDir("obj_mesh_read");
  writeFile(dir / "m.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
            "f 1/1/1 2/2/1 3/2/1 4/1/1\nf 1//1 3//1 4//1\nf -4 -3 -2\n");
  auto mesh = importers::readObjPolygonMesh(dir / "m.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->positions.size(), 4u);
  ASSERT_EQ(mesh->faceCount(), 3u);
  EXPECT_EQ(mesh->faceSize(0), 4u);
  EXPECT_EQ(mesh->corner(0, 2).v, 2);
  EXPECT_EQ(mesh->corner(0, 2).vt, 1);
  EXPECT_EQ(mesh->corner(0, 2).vn, 0);
  EXPECT_EQ(mesh->corner(1, 0).vt, -1) << "v//vn has no texcoord";
  EXPECT_EQ(mesh->corner(2, 0).v, 0) << "negative indices are relative";
  EXPECT_EQ(mesh->corner(2, 0).vn, -1);
  EXPECT_EQ(mesh->faceMaterial, (std::vector<int>{-1, -1, -1}));
}

// MeshLab's and ZBrush's vertex colours ('v x y z r g b'), kept only when
// every vertex has one.
TEST(ObjMesh, ReadsVertexColoursWhenEveryVertexHasOne) {
  const auto dir = freshTempDir("obj_mesh_colours");
  writeFile(dir / "painted.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 1 1 0 0 0 1\nf 1 2 3\n");
  auto painted = importers::readObjPolygonMesh(dir / "painted.obj");
  ASSERT_TRUE(painted.ok()) << painted.error().message;
  EXPECT_EQ(painted->colors, (std::vector<glm::vec3>{{1, 0, 0}, {0, 0.5f, 0}, {0, 0, 1}}));
  writeFile(dir / "partly.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  auto partly = importers::readObjPolygonMesh(dir / "partly.obj");
  ASSERT_TRUE(partly.ok()) << partly.error().message;
  EXPECT_TRUE(partly->colors.empty());
}

TEST(ObjMeshBadInput, MissingEmptyAndFacelessFiles) {
  const auto dir = freshTempDir("obj_mesh_bad_files");
  auto missing = importers::readObjPolygonMesh(dir / "none.obj");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("none.obj: file not found"), std::string::npos);
  writeFile(dir / "empty.obj", "");
  auto empty = importers::readObjPolygonMesh(dir / "empty.obj");
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().message.find("no vertices"), std::string::npos) << empty.error().message;
  writeFile(dir / "points.obj", "v 0 0 0\nv 1 0 0\n");
  auto points = importers::readObjPolygonMesh(dir / "points.obj");
  ASSERT_FALSE(points.ok());
  EXPECT_NE(points.error().message.find("no faces"), std::string::npos) << points.error().message;
}

TEST(ObjMeshBadInput, IndexOutOfRangeNamesTheFace) {
  const auto dir = freshTempDir("obj_mesh_bad_index");
  writeFile(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2 9\n");
  auto mesh = importers::readObjPolygonMesh(dir / "m.obj");
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("m.obj: face 2 uses vertex 9, the file has 3"), std::string::npos)
      << mesh.error().message;
  writeFile(dir / "n.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n");
  mesh = importers::readObjPolygonMesh(dir / "n.obj");
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("face 1 uses normal 4, the file has 1"), std::string::npos) << mesh.error().message;
}

TEST(ObjMeshBadInput, NonFiniteNumbers) {
  // tinyobjloader reads "nan"/"inf" words as 0 but overflowing literals as infinity.
  const auto dir = freshTempDir("obj_mesh_nan");
  writeFile(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 1 1 1e400\nf 1 2 3\n");
  auto mesh = importers::readObjPolygonMesh(dir / "m.obj");
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("m.obj: vertex 3 is infinite"), std::string::npos) << mesh.error().message;
  writeFile(dir / "n.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 -1e999 0\nf 1//1 2//1 3//1\n");
  mesh = importers::readObjPolygonMesh(dir / "n.obj");
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("normal 1 is infinite"), std::string::npos) << mesh.error().message;
}

TEST(ObjMeshBadInput, MaterialLibraryOutsideTheFolderIsRefusedWithAWarning) {
  const auto dir = freshTempDir("obj_mesh_mtl_outside");
  writeFile(dir / "secret.mtl", "newmtl secret\nKd 1 0 0\n");
  writeFile(dir / "sub" / "m.obj", "mtllib ../secret.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl secret\nf 1 2 3\n");
  auto mesh = importers::readObjPolygonMesh(dir / "sub" / "m.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_TRUE(mesh->materials.empty());
  const bool refused = std::any_of(mesh->warnings.begin(), mesh->warnings.end(), [](const std::string& w) {
    return w.find("'../secret.mtl' is outside the OBJ's folder") != std::string::npos;
  });
  EXPECT_TRUE(refused);
}

}  // namespace
