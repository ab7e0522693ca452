// Spatial hash queries agree with brute force.
#include <random>

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

}  // namespace
