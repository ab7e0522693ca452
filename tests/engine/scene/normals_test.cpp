// Generated smooth normals for meshes without NORMAL.
#include <gtest/gtest.h>

#include "engine/scene/normals.h"

namespace {

void expectVec(const glm::vec3& got, const glm::vec3& want) {
  EXPECT_NEAR(got.x, want.x, 1e-5f);
  EXPECT_NEAR(got.y, want.y, 1e-5f);
  EXPECT_NEAR(got.z, want.z, 1e-5f);
}

TEST(SmoothNormals, FlatQuadPointsAlongItsFaceNormal) {
  const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  for (const glm::vec3& n : eng::computeSmoothNormals(pos, idx)) expectVec(n, {0, 0, 1});
}

TEST(SmoothNormals, SplitCornerVerticesShareOneAveragedNormal) {
  // Three faces of a cube corner at the origin, each with its own copy of the corner vertex.
  const std::vector<glm::vec3> pos = {
      {0, 0, 0}, {0, 1, 0}, {1, 0, 0},   // z = 0 face, normal -z
      {0, 0, 0}, {0, 0, 1}, {0, 1, 0},   // x = 0 face, normal -x
      {0, 0, 0}, {1, 0, 0}, {0, 0, 1}};  // y = 0 face, normal -y
  const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const auto normals = eng::computeSmoothNormals(pos, idx);
  const float k = -1.0f / std::sqrt(3.0f);
  for (int corner : {0, 3, 6}) expectVec(normals[corner], {k, k, k});
}

TEST(SmoothNormals, UnusedVerticesAndBadTrianglesAreHarmless) {
  const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 1, 99};
  const auto normals = eng::computeSmoothNormals(pos, idx);
  expectVec(normals[0], {0, 0, 1});
  expectVec(normals[3], {0, 0, 1});
}

}  // namespace
