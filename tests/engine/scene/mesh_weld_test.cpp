#include "engine/scene/mesh_weld.h"

#include <gtest/gtest.h>

namespace {

// A unit square as two triangles, each corner its own vertex (a soup).
eng::Primitive squareSoup() {
  eng::Primitive p;
  const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int c : {0, 1, 2, 0, 2, 3}) {
    p.positions.push_back(corners[c]);
    p.normals.push_back({0, 0, 1});
    p.texcoords.push_back(glm::vec2(corners[c]));
    p.indices.push_back(uint32_t(p.indices.size()));
  }
  return p;
}

TEST(MeshWeld, ASoupsCopiesBecomeOneVertexAndTheTrianglesStay) {
  eng::Primitive p = squareSoup();
  EXPECT_EQ(eng::weldIdenticalVertices(p), 2u);
  ASSERT_EQ(p.vertexCount(), 4u);
  ASSERT_EQ(p.normals.size(), 4u);
  ASSERT_EQ(p.texcoords.size(), 4u);
  ASSERT_EQ(p.indices.size(), 6u);
  // The triangles share the diagonal's two vertices now, at the same places as before.
  EXPECT_EQ(p.indices[0], p.indices[3]);
  EXPECT_EQ(p.indices[2], p.indices[4]);
  const glm::vec3 expected[6] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(p.positions[p.indices[i]], expected[i]) << i;
  EXPECT_EQ(eng::weldIdenticalVertices(p), 0u) << "nothing left to weld";
}

// Copies that differ in any attribute are a UV seam, a hard edge, a cut
// made on purpose: they stay apart.
TEST(MeshWeld, CopiesThatDifferInAnyAttributeStayApart) {
  eng::Primitive uv = squareSoup();
  uv.texcoords[3] = {0.5f, 0.5f};  // the second triangle's first corner on another UV island
  EXPECT_EQ(eng::weldIdenticalVertices(uv), 1u);
  EXPECT_EQ(uv.vertexCount(), 5u);

  eng::Primitive morphed = squareSoup();
  morphed.targets.resize(1);
  morphed.targets[0].positions.assign(6, glm::vec3(0.0f));
  morphed.targets[0].positions[4] = {0, 0, 0.1f};  // the diagonal's far end moves on one side only
  EXPECT_EQ(eng::weldIdenticalVertices(morphed), 1u);
  ASSERT_EQ(morphed.targets[0].positions.size(), 5u);
  EXPECT_EQ(morphed.targets[0].positions[morphed.indices[4]], glm::vec3(0, 0, 0.1f));
  EXPECT_EQ(morphed.targets[0].positions[morphed.indices[2]], glm::vec3(0.0f));

  eng::Primitive skinned = squareSoup();
  skinned.joints.assign(6, glm::u16vec4(0));
  skinned.jointWeights.assign(6, glm::vec4(1, 0, 0, 0));
  skinned.joints[3] = glm::u16vec4(1, 0, 0, 0);
  EXPECT_EQ(eng::weldIdenticalVertices(skinned), 1u);
  EXPECT_EQ(skinned.joints.size(), 5u);
  EXPECT_EQ(skinned.jointWeights.size(), 5u);
}

TEST(MeshWeld, AMalformedPrimitiveIsLeftAsItIs) {
  eng::Primitive p = squareSoup();
  p.indices.push_back(99);  // past the vertices
  EXPECT_EQ(eng::weldIdenticalVertices(p), 0u);
  EXPECT_EQ(p.vertexCount(), 6u);
  eng::Primitive short_ = squareSoup();
  short_.normals.pop_back();  // one normal short
  EXPECT_EQ(eng::weldIdenticalVertices(short_), 0u);
}

}  // namespace
