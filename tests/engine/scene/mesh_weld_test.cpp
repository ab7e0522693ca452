#include "engine/scene/mesh_weld.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>

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


// Triangles as a flat-shaded soup: each corner its own vertex, its normal its
// triangle's, its UV its x and y.
eng::Primitive flatSoup(std::initializer_list<std::array<glm::vec3, 3>> triangles) {
  eng::Primitive p;
  for (const auto& t : triangles) {
    const glm::vec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
    for (const glm::vec3& c : t) {
      p.positions.push_back(c);
      p.normals.push_back(n);
      p.texcoords.push_back(glm::vec2(c));
      p.indices.push_back(uint32_t(p.indices.size()));
    }
  }
  return p;
}

// A roof: two faces meeting along the x axis, each falling `degrees` below
// the level (5: nearly flat; 85: a knife edge), normals outward. `crack`:
// one face on the floor and one rising `degrees` from it, normals into the
// wedge between them (two sheets closing onto each other).
eng::Primitive roof(float degrees, bool crack = false) {
  const float a = glm::radians(degrees);
  const glm::vec3 o(0, 0, 0), x(1, 0, 0);
  if (crack) {
    const glm::vec3 floor(0.0f, 0.0f, -1.0f), rising(0.0f, std::sin(a), -std::cos(a));
    return flatSoup({{{o, x, floor}}, {{o, rising, x}}});
  }
  const glm::vec3 left(0.0f, -std::sin(a), -std::cos(a)), right(0.0f, -std::sin(a), std::cos(a));
  return flatSoup({{{o, x, left}}, {{x, o, right}}});
}

// A flat-shaded surface's copies are merged where asked (its shape's
// topology for the autorig), their normal the copies' mean; left apart otherwise.
TEST(MeshWeld, CopiesSplitOnlyByShadingAreWeldedAcrossHardEdgesWhenAsked) {
  eng::Primitive kept = roof(30.0f);
  EXPECT_EQ(eng::weldIdenticalVertices(kept), 0u) << "their normals differ";
  for (float degrees : {5.0f, 30.0f, 60.0f, 85.0f}) {  // a knife edge is still one surface
    eng::Primitive p = roof(degrees);
    EXPECT_EQ(eng::weldIdenticalVertices(p, {.acrossHardEdges = true}), 2u) << degrees;
    ASSERT_EQ(p.vertexCount(), 4u);
    EXPECT_NEAR(glm::length(p.normals[p.indices[0]] - glm::vec3(0, 1, 0)), 0.0f, 1e-5f) << "the mean of the two faces'";
  }
  eng::Primitive uvSeam = roof(30.0f);
  uvSeam.texcoords[3] += glm::vec2(0.5f);
  EXPECT_EQ(eng::weldIdenticalVertices(uvSeam, {.acrossHardEdges = true}), 1u) << "the UV seam's corner stays apart";
}

// Two sheets that touch along an edge (a slit mouth's lips) are not one
// surface there: a narrow crack, each face's normal towards the other, stays
// apart; a wide valley is a hard edge.
TEST(MeshWeld, TwoSheetsClosingIntoACrackStayApart) {
  eng::Primitive crack = roof(30.0f, true);
  EXPECT_EQ(eng::weldIdenticalVertices(crack, {.acrossHardEdges = true}), 0u);
  eng::Primitive valley = roof(150.0f, true);
  EXPECT_EQ(eng::weldIdenticalVertices(valley, {.acrossHardEdges = true}), 2u);
}

// Four faces on one edge: two lips, each a wedge (its front and its inside
// meeting at the edge). Each face joins the face that closes its own lip,
// not the other lip's face beside it.
TEST(MeshWeld, AnEdgeOnFourFacesJoinsTheFacesOfOneSolid) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0);
  const glm::vec3 upFront(0, 1, 1), upBack(0, 1, -1), downFront(0, -1, 1), downBack(0, -1, -1);
  // Windings give outward normals: the upper lip's faces look away from its
  // wedge (front-up and back-up), the lower lip's likewise.
  eng::Primitive lips = flatSoup({{{a, b, upFront}}, {{b, a, upBack}}, {{b, a, downFront}}, {{a, b, downBack}}});
  ASSERT_GT(glm::dot(lips.normals[0], glm::vec3(0, 0, 1)), 0.5f);
  EXPECT_EQ(eng::weldIdenticalVertices(lips, {.acrossHardEdges = true}), 4u);
  ASSERT_EQ(lips.vertexCount(), 8u);
  EXPECT_EQ(lips.indices[0], lips.indices[4]) << "the upper lip's faces share their corner at a";
  EXPECT_EQ(lips.indices[7], lips.indices[9]) << "the lower lip's too";
  EXPECT_NE(lips.indices[0], lips.indices[9]) << "the lips stay apart";
}

// Welded for the rig, split again after it: each corner gets its own normal
// back, a target made on the welded mesh moves both copies, and its normal
// deltas along the ridge are each side's own face turning.
TEST(MeshWeld, RestoringHardEdgesGivesEachCornerItsNormalAndEachSideItsDeltas) {
  const eng::Primitive original = roof(40.0f);
  eng::Primitive p = original;
  ASSERT_EQ(eng::weldIdenticalVertices(p, {.acrossHardEdges = true}), 2u);
  eng::MorphTarget lift;  // the ridge's far end raised: both faces turn
  lift.positions.assign(p.vertexCount(), glm::vec3(0.0f));
  lift.normals.assign(p.vertexCount(), glm::vec3(0.0f));
  for (size_t v = 0; v < p.vertexCount(); ++v)
    if (p.positions[v] == glm::vec3(1, 0, 0)) lift.positions[v] = {0, 0.5f, 0};
  p.targets.push_back(lift);
  EXPECT_EQ(eng::restoreHardEdges(p, original), 2u);
  ASSERT_EQ(p.vertexCount(), 6u);
  for (size_t c = 0; c < 6; ++c) {
    const uint32_t v = p.indices[c];
    EXPECT_EQ(p.normals[v], original.normals[c]) << c;
    EXPECT_EQ(p.positions[v], original.positions[c]) << c;
    EXPECT_EQ(p.targets[0].positions[v], original.positions[c] == glm::vec3(1, 0, 0) ? glm::vec3(0, 0.5f, 0) : glm::vec3(0.0f)) << c;
  }
  for (size_t t = 0; t < 2; ++t) {
    glm::vec3 moved[3];
    for (size_t k = 0; k < 3; ++k) moved[k] = p.positions[p.indices[t * 3 + k]] + p.targets[0].positions[p.indices[t * 3 + k]];
    const glm::vec3 turned = glm::normalize(glm::cross(moved[1] - moved[0], moved[2] - moved[0]));
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = p.indices[t * 3 + k];
      if (p.positions[v].y != 0.0f) continue;  // off the ridge: one vertex, its deltas the rig's
      EXPECT_NEAR(glm::length(p.normals[v] + p.targets[0].normals[v] - turned), 0.0f, 1e-5f) << t << " " << k;
    }
  }
}

// A face's own targets keep their normal deltas through the weld and back.
TEST(MeshWeld, RestoringHardEdgesKeepsTheOriginalsOwnTargets) {
  eng::Primitive original = roof(40.0f);
  eng::MorphTarget own;
  own.positions.assign(6, glm::vec3(0.0f, 0.0f, 0.1f));  // a shift: both copies alike
  own.normals.assign(6, glm::vec3(0.0f));
  own.normals[0] = {0.1f, 0.0f, 0.0f};  // written by its exporter, per corner
  original.targets.push_back(own);
  eng::Primitive p = original;
  ASSERT_EQ(eng::weldIdenticalVertices(p, {.acrossHardEdges = true}), 2u);
  eng::restoreHardEdges(p, original);
  for (size_t c = 0; c < 6; ++c) EXPECT_EQ(p.targets[0].normals[p.indices[c]], original.targets[0].normals[c]) << c;
}


// Welded and restored, any mesh draws as it did: every corner at its place
// with its normal, UV and skin, whatever was welded in between (a bumpy grid
// flat-shaded, with hard edges, seams, doubled faces, a degenerate triangle
// and a NaN corner: nothing crashes, nothing moves).
TEST(MeshWeld, WeldedAndRestoredEveryCornerDrawsAsBefore) {
  uint32_t seed = 12345u;
  auto next = [&seed] { return (seed = seed * 1664525u + 1013904223u) >> 8; };
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::array<glm::vec3, 3>> triangles;
    const int n = 6;  // a 6 x 6 grid of squares, each one's far corner lifted at random
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec3 a(float(x), float(y), 0.0f), b(float(x + 1), float(y), 0.0f), c(float(x + 1), float(y + 1), 0.0f),
            d(float(x), float(y + 1), 0.0f);
        const float lift = float(next() % 5) * 0.2f;
        triangles.push_back({a, b, c + glm::vec3(0, 0, lift)});
        triangles.push_back({a, c + glm::vec3(0, 0, lift), d});
      }
    triangles.push_back(triangles[3]);                           // a doubled face
    triangles.push_back({glm::vec3(0), glm::vec3(0), glm::vec3(1, 0, 0)});  // degenerate
    eng::Primitive original = flatSoup({});
    for (const auto& t : triangles) {
      glm::vec3 n0 = glm::cross(t[1] - t[0], t[2] - t[0]);
      n0 = glm::length(n0) > 0.0f ? glm::normalize(n0) : glm::vec3(0, 0, 1);
      for (const glm::vec3& c : t) {
        original.positions.push_back(c);
        // Smooth where the trial says so (then the copies are identical), flat elsewhere.
        original.normals.push_back(next() % 3 == 0 ? glm::vec3(0, 0, 1) : n0);
        original.texcoords.push_back(glm::vec2(c) + (next() % 11 == 0 ? glm::vec2(0.5f) : glm::vec2(0.0f)));
        original.indices.push_back(uint32_t(original.indices.size()));
      }
    }
    if (trial % 4 == 3) original.positions[7] = glm::vec3(NAN);
    eng::Primitive p = original;
    eng::weldIdenticalVertices(p, {.acrossHardEdges = true});
    ASSERT_EQ(p.indices.size(), original.indices.size());
    eng::restoreHardEdges(p, original);
    ASSERT_EQ(p.indices.size(), original.indices.size());
    for (size_t c = 0; c < p.indices.size(); ++c) {
      const uint32_t v = p.indices[c];
      ASSERT_LT(v, p.vertexCount());
      if (std::isnan(original.positions[c].x)) continue;
      EXPECT_EQ(p.positions[v], original.positions[c]) << trial << " corner " << c;
      EXPECT_EQ(p.texcoords[v], original.texcoords[c]) << trial << " corner " << c;
      // A NaN corner's triangle finds no match and keeps the welded mean.
      const size_t first = c - c % 3;
      const bool whole = !std::isnan(original.positions[first].x) && !std::isnan(original.positions[first + 1].x) &&
                         !std::isnan(original.positions[first + 2].x);
      if (whole) {
        EXPECT_EQ(p.normals[v], original.normals[c]) << trial << " corner " << c;
      }
    }
  }
}

}  // namespace
