// Levels of detail over the same vertices (eng::buildLodChain).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <utility>

#include "engine/scene/mesh_lod.h"
#include "engine/scene/model.h"

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

// The triangles of a list as sorted index triples (a level may rotate none: it copies kept ones).
std::multiset<std::array<uint32_t, 3>> triangles(const std::vector<uint32_t>& indices) {
  std::multiset<std::array<uint32_t, 3>> out;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) out.insert({indices[t], indices[t + 1], indices[t + 2]});
  return out;
}

TEST(MeshLod, KeptTrianglesAreInEveryLevelAsTheyAre) {
  // A band of rings across the cap is kept (a painted line, a crease).
  const Grid g = cap(60, 80);
  std::vector<uint8_t> keep(g.indices.size() / 3, 0);
  std::vector<uint32_t> band;
  for (size_t t = 0; t < keep.size(); ++t) {
    const size_t ring = t / (2 * 80);
    if (ring >= 20 && ring < 23) {
      keep[t] = 1;
      band.insert(band.end(), g.indices.begin() + std::ptrdiff_t(3 * t), g.indices.begin() + std::ptrdiff_t(3 * t + 3));
    }
  }
  const auto levels = eng::buildLodChain(g.positions, g.indices, {}, keep);
  ASSERT_GE(levels.size(), 2u) << "the rest still simplifies";
  const auto kept = triangles(band);
  const auto outline = borderEdges(band), capRim = borderEdges(g.indices);
  for (const eng::LodLevel& level : levels) {
    const auto all = triangles(level.indices);
    for (const auto& t : kept) EXPECT_EQ(all.count(t), kept.count(t)) << "a kept triangle changed";
    // No crack: every edge of the band's outline is still shared by a triangle outside the band.
    const auto levelBorder = borderEdges(level.indices);
    for (const auto& e : outline)
      if (!capRim.count(e)) {
        EXPECT_FALSE(levelBorder.count(e)) << "edge " << e.first << "-" << e.second;
      }
  }
  EXPECT_LT(levels.back().indices.size(), g.indices.size() / 2);
  // Flags of the wrong length are no flags.
  EXPECT_EQ(eng::buildLodChain(g.positions, g.indices, {}, std::vector<uint8_t>(7, 1)).size(),
            eng::buildLodChain(g.positions, g.indices).size());
}

TEST(MeshLod, PaintedLinesCreasesAndCornerColoursAreKept) {
  // Two triangles side by side in uv: the left over plain skin, the right over a one-texel dark line.
  eng::Image texture{.name = "skin", .width = 64, .height = 64};
  texture.rgba8.assign(64 * 64 * 4, 0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      uint8_t* p = &texture.rgba8[size_t(y * 64 + x) * 4];
      const uint8_t grain = uint8_t((x * 7 + y * 13) % 9);  // skin grain: a few levels
      p[0] = uint8_t(210 + grain), p[1] = uint8_t(160 + grain), p[2] = uint8_t(140 + grain), p[3] = 255;
      if (x == 45) p[0] = p[1] = p[2] = 30;  // the lash line
    }
  const std::vector<glm::vec2> uv{{0.05f, 0.1f}, {0.45f, 0.1f}, {0.25f, 0.9f}, {0.55f, 0.1f}, {0.95f, 0.1f}, {0.75f, 0.9f}};
  const std::vector<uint32_t> indices{0, 1, 2, 3, 4, 5};
  const std::vector<glm::vec3> flat(6, glm::vec3(0, 0, 1));
  EXPECT_EQ(eng::keptTriangles(indices, uv, &texture, {}, flat, 6), (std::vector<uint8_t>{0, 1}));
  EXPECT_EQ(eng::keptTriangles(indices, uv, nullptr, {}, flat, 6), (std::vector<uint8_t>{0, 0})) << "no texture";
  // Corner colours: a painted edge across the first triangle.
  std::vector<glm::vec4> colours(6, glm::vec4(0.8f, 0.6f, 0.5f, 1.0f));
  colours[1] = glm::vec4(0.2f, 0.1f, 0.1f, 1.0f);
  EXPECT_EQ(eng::keptTriangles(indices, {}, nullptr, colours, flat, 6), (std::vector<uint8_t>{1, 0}));
  // A crease: the second triangle's corner normals turn 45 degrees.
  std::vector<glm::vec3> normals = flat;
  normals[4] = glm::normalize(glm::vec3(1, 0, 1));
  EXPECT_EQ(eng::keptTriangles(indices, {}, nullptr, {}, normals, 6), (std::vector<uint8_t>{0, 1}));
  // Arrays not one per vertex, and indices past the vertices, flag nothing.
  EXPECT_EQ(eng::keptTriangles(indices, {}, nullptr, colours, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)), 6),
            (std::vector<uint8_t>{1, 0}));
  EXPECT_EQ(eng::keptTriangles(std::vector<uint32_t>{0, 1, 99}, uv, &texture, colours, normals, 6), (std::vector<uint8_t>{0}));
}

TEST(MeshLod, CreasesATargetMakesAreKept) {
  // Two flat triangles; a target turns one corner's normal 60 degrees (a fold at that pose only).
  eng::Primitive prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}};
  prim.normals.assign(6, glm::vec3(0, 0, 1));
  prim.indices = {0, 1, 2, 3, 4, 5};
  EXPECT_EQ(eng::keptTriangles(prim, nullptr), (std::vector<uint8_t>{0, 0})) << "smooth at rest";
  eng::MorphTarget fold;
  fold.positions.assign(6, glm::vec3(0.0f));
  fold.normals.assign(6, glm::vec3(0.0f));
  fold.normals[4] = glm::vec3(std::sqrt(3.0f), 0, 0);  // (0,0,1) + this: 60 degrees off
  prim.targets.push_back(fold);
  EXPECT_EQ(eng::keptTriangles(prim, nullptr), (std::vector<uint8_t>{0, 1}));
  prim.targets[0].normals.resize(3);  // not one per vertex: ignored
  EXPECT_EQ(eng::keptTriangles(prim, nullptr), (std::vector<uint8_t>{0, 0}));
}

TEST(MeshLod, SmallListsGetNoLevels) {
  const Grid g = cap(10, 12);  // 240 triangles
  EXPECT_TRUE(eng::buildLodChain(g.positions, g.indices).empty());
  EXPECT_TRUE(eng::buildLodChain({}, {}).empty());
}

}  // namespace
