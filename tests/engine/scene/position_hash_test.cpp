// Spatial hash queries agree with brute force.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/position_hash.h"

namespace {

TEST(PositionHash, FindsExactlyThePointsWithinTheRadiusNearestFirst) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> points(5000);
  for (glm::vec3& p : points) p = {u(rng), u(rng), u(rng)};
  const float radius = 0.05f;
  const eng::PositionHash hash(points, radius);
  for (int q = 0; q < 300; ++q) {
    const glm::vec3 p = q % 2 ? points[q] : glm::vec3(u(rng), u(rng), u(rng));
    const float r = q % 3 == 0 ? radius * 0.3f : radius;
    std::vector<uint32_t> brute;
    for (uint32_t i = 0; i < points.size(); ++i)
      if (glm::dot(points[i] - p, points[i] - p) <= r * r) brute.push_back(i);
    std::vector<uint32_t> found = hash.near(p, r);
    for (size_t i = 1; i < found.size(); ++i)
      EXPECT_LE(glm::length(points[found[i - 1]] - p), glm::length(points[found[i]] - p));
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, brute) << "query " << q;
  }
}

TEST(PositionHash, NegativeCoordinatesAndCellBordersAreHandled) {
  const std::vector<glm::vec3> points = {{-0.001f, 0, 0}, {0.001f, 0, 0}, {-5, -5, -5}};
  const eng::PositionHash hash(points, 0.01f);
  EXPECT_EQ(hash.near({0, 0, 0}, 0.01f).size(), 2u);
  EXPECT_EQ(hash.near({-5, -5, -5}, 0.01f), std::vector<uint32_t>{2});
  EXPECT_TRUE(hash.near({3, 3, 3}, 0.01f).empty());
}

// Seam copies (bit-identical positions, -0.0 and +0.0 as one) are one
// group, numbered by first appearance, each naming its lowest vertex; a
// position one float step away is another group.
TEST(ExactPositionGroups, CopiesAtOnePlaceAreOneGroupNumberedByFirstVertex) {
  const float nextToOne = std::nextafter(1.0f, 2.0f);
  const std::vector<glm::vec3> positions = {{1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {-0.0f, 0, 0}, {nextToOne, 0, 0}, {0, 1, 0}};
  const eng::ExactPositionGroups groups = eng::groupExactPositions(positions);
  EXPECT_EQ(groups.groupOf, (std::vector<uint32_t>{0, 1, 0, 1, 2, 3}));
  EXPECT_EQ(groups.firstVertex, (std::vector<uint32_t>{0, 1, 4, 5}));
  EXPECT_TRUE(eng::groupExactPositions({}).firstVertex.empty());
}

// Against the obvious quadratic grouping on a mesh's worth of points with many copies.
TEST(ExactPositionGroups, AgreesWithComparingEveryPair) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> pick(0, 299);
  std::vector<glm::vec3> places(300), positions(2000);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (glm::vec3& p : places) p = {u(rng), u(rng), u(rng)};
  for (glm::vec3& p : positions) p = places[size_t(pick(rng))];
  const eng::ExactPositionGroups groups = eng::groupExactPositions(positions);
  std::vector<uint32_t> firstVertex;
  for (size_t v = 0; v < positions.size(); ++v) {
    size_t first = 0;
    while (positions[first] != positions[v]) ++first;
    if (first == v) firstVertex.push_back(uint32_t(v));
    ASSERT_LT(groups.groupOf[v], groups.firstVertex.size());
    EXPECT_EQ(groups.firstVertex[groups.groupOf[v]], first) << v;
  }
  EXPECT_EQ(groups.firstVertex, firstVertex);
}

}  // namespace
