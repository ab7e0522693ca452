// Levels of detail over the same vertices (eng::buildLodChain).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "engine/scene/mesh_lod.h"

namespace {

// A open hemisphere-like cap: rings x segments quads, the rim ring a border.
struct Grid {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
};

Grid cap(int rings, int segments) {
  Grid g;
  for (int r = 0; r <= rings; ++r) {
    const float theta = 1.2f * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 6.2831853f * float(s) / float(segments);
      g.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
    }
  }
  const auto at = [&](int r, int s) { return uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      g.indices.insert(g.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      g.indices.insert(g.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  return g;
}

// Edges used by exactly one triangle.
std::set<std::pair<uint32_t, uint32_t>> borderEdges(const std::vector<uint32_t>& indices) {
  std::multiset<std::pair<uint32_t, uint32_t>> all;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = indices[t + e], b = indices[t + (e + 1) % 3];
      all.insert({std::min(a, b), std::max(a, b)});
    }
  std::set<std::pair<uint32_t, uint32_t>> once;
  for (const auto& e : all)
    if (all.count(e) == 1) once.insert(e);
  return once;
}

TEST(MeshLod, LevelsShrinkErrorsGrowAndIndicesStayInTheVertexBuffer) {
  const Grid g = cap(60, 80);
  const auto levels = eng::buildLodChain(g.positions, g.indices);
  ASSERT_GE(levels.size(), 3u);
  size_t previousCount = g.indices.size();
  float previousError = 0.0f;
  for (const eng::LodLevel& level : levels) {
    ASSERT_EQ(level.indices.size() % 3, 0u);
    EXPECT_LT(level.indices.size(), previousCount);
    EXPECT_GE(level.error, previousError);
    EXPECT_LT(level.error, 0.02f * 2.0f);  // within the relative bound of a 2-unit-wide cap
    for (uint32_t i : level.indices) ASSERT_LT(i, g.positions.size());
    previousCount = level.indices.size();
    previousError = level.error;
  }
  EXPECT_LE(levels[0].indices.size(), g.indices.size() * 8 / 10);
}

TEST(MeshLod, BordersKeepEveryVertex) {
  // The rim of an opening (an eye, the mouth, the neck's cut) must not move.
  const Grid g = cap(40, 64);
  std::set<uint32_t> rim;
  for (const auto& [a, b] : borderEdges(g.indices)) rim.insert({a, b});
  for (const eng::LodLevel& level : eng::buildLodChain(g.positions, g.indices)) {
    std::set<uint32_t> kept;
    for (const auto& [a, b] : borderEdges(level.indices)) kept.insert({a, b});
    EXPECT_EQ(kept, rim);
  }
}

TEST(MeshLod, SmallListsGetNoLevels) {
  const Grid g = cap(10, 12);  // 240 triangles
  EXPECT_TRUE(eng::buildLodChain(g.positions, g.indices).empty());
  EXPECT_TRUE(eng::buildLodChain({}, {}).empty());
}

}  // namespace
