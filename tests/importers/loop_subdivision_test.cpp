// Loop subdivision of low-polygon faces (the CANDIDE-3 mask): counts, the
// boundary and interior rules, and morph targets carried by the same weights.
#include "importers/loop_subdivision.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "importers/candide_import.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

// A unit square of two triangles facing +z (every edge but the diagonal is a boundary).
eng::Primitive square() {
  eng::Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  p.normals.assign(4, glm::vec3(0, 0, 1));
  p.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  p.indices = {0, 1, 2, 0, 2, 3};
  eng::MorphTarget lift;  // moves the whole sheet up by 0.5
  lift.positions.assign(4, glm::vec3(0, 0, 0.5f));
  eng::MorphTarget corner;  // pulls vertex 2 only
  corner.positions = {glm::vec3(0), glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(0)};
  p.targets = {lift, corner};
  return p;
}

TEST(LoopSubdivision, SquareSplitsIntoEightTrianglesWithBoundaryRules) {
  eng::Primitive p = square();
  ASSERT_TRUE(importers::loopSubdivide(p, "square"));
  EXPECT_EQ(p.positions.size(), 9u);  // 4 corners + 5 edges
  EXPECT_EQ(p.indices.size(), 24u);
  ASSERT_EQ(p.texcoords.size(), 9u);
  // Corner 0 lies on two boundary edges (to 1 and 3): 3/4 own + 1/8 each.
  EXPECT_NEAR(p.positions[0].x, 0.125f, 1e-6f);
  EXPECT_NEAR(p.positions[0].y, 0.125f, 1e-6f);
  // Boundary edge midpoints stay midpoints; the diagonal takes 3/8, 3/8, 1/8, 1/8 (= its midpoint on a flat square).
  for (size_t v = 4; v < 9; ++v) EXPECT_NEAR(p.positions[v].z, 0.0f, 1e-6f);
  for (const glm::vec3& n : p.normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f);
  // Targets: a uniform lift stays uniform (rows sum to one); a single-vertex pull spreads by the same weights.
  for (const glm::vec3& d : p.targets[0].positions) EXPECT_NEAR(d.z, 0.5f, 1e-6f);
  EXPECT_NEAR(p.targets[1].positions[2].z, 0.75f, 1e-6f);
  EXPECT_NEAR(p.targets[1].positions[0].z, 0.0f, 1e-6f);
  EXPECT_EQ(p.targets[1].normals.size(), 9u);
}

// A scan's paint: old vertices keep their colour, edge vertices take their
// edge's midpoint (colours are painted, not shaped by Loop's weights).
TEST(LoopSubdivision, VertexColoursAreKeptAndMidpointsAtNewVertices) {
  eng::Primitive p = square();
  p.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 0.5f}};
  ASSERT_TRUE(importers::loopSubdivide(p, "square"));
  ASSERT_EQ(p.colors.size(), p.positions.size());
  EXPECT_EQ(p.colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(p.colors[3], glm::vec4(1, 1, 1, 0.5f));
  // The new vertices are the 5 edges' midpoints, in the edges' order.
  const std::vector<glm::vec4> midpoints = {{0.5f, 0.5f, 0, 1}, {0, 0.5f, 0.5f, 1}, {0.5f, 0, 0.5f, 1},
                                            {0.5f, 0.5f, 1, 0.75f}, {1, 0.5f, 0.5f, 0.75f}};
  const auto cmp = [](const glm::vec4& a, const glm::vec4& b) {
    return std::lexicographical_compare(&a.x, &a.x + 4, &b.x, &b.x + 4);
  };
  std::vector<glm::vec4> made(p.colors.begin() + 4, p.colors.end()), expected = midpoints;
  std::sort(made.begin(), made.end(), cmp);
  std::sort(expected.begin(), expected.end(), cmp);
  EXPECT_EQ(made, expected);
}

TEST(LoopSubdivision, CandideMaskBecomesSmoothWithItsUnits) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(testing_support::sharedDir() / "candide3" / "candide3.wfm");
  ASSERT_TRUE(model) << model.error().message;
  eng::Primitive& p = model->meshes[0].primitives[0];
  const size_t targets = p.targets.size();
  ASSERT_TRUE(importers::loopSubdivide(p, "candide3"));
  EXPECT_EQ(p.indices.size() / 3, (184u - 28u) * 4);  // less the skin inside the eye openings (candide_eyes.h)
  EXPECT_EQ(p.targets.size(), targets);
  for (const eng::MorphTarget& t : p.targets) EXPECT_EQ(t.positions.size(), p.positions.size());
  for (const glm::vec3& n : p.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
}

TEST(LoopSubdivisionValidity, BrokenIndicesAreNamed) {
  eng::Primitive p = square();
  p.indices.push_back(0);
  auto r = importers::loopSubdivide(p, "mask");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "mask: 7 indices is not a triangle list");
  p = square();
  p.indices[5] = 9;
  r = importers::loopSubdivide(p, "mask");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "mask: index 9 of 4 vertices");
}

}  // namespace
}  // namespace facial
