// The CPU reference morph: base + sum(w_i * delta_i), normals renormalised.
#include <stdexcept>

#include <gtest/gtest.h>

#include "engine/scene/cpu_morph.h"

namespace {

eng::Primitive triangleWithTwoTargets() {
  eng::Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  p.indices = {0, 1, 2};
  eng::MorphTarget raise;
  raise.positions = {{0, 0, 1}, {0, 0, 0}, {0, 0, 2}};
  raise.normals = {{1, 0, -1}, {0, 0, 0}, {0, 0, 0}};
  eng::MorphTarget slide;  // positions only
  slide.positions = {{4, 0, 0}, {0, 4, 0}, {0, 0, 0}};
  p.targets = {raise, slide};
  return p;
}

void expectVec(const glm::vec3& got, const glm::vec3& want) {
  EXPECT_NEAR(got.x, want.x, 1e-6f);
  EXPECT_NEAR(got.y, want.y, 1e-6f);
  EXPECT_NEAR(got.z, want.z, 1e-6f);
}

TEST(CpuMorph, BlendsPositionsLinearlyAndRenormalisesNormals) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3), nrm(3);
  const float weights[] = {0.5f, 0.25f};
  eng::morphPrimitiveCpu(p, weights, pos, nrm);
  expectVec(pos[0], {0 + 0.25f * 4, 0, 0.5f * 1});  // (1, 0, 0.5)
  expectVec(pos[1], {1, 0.25f * 4, 0});             // (1, 1, 0)
  expectVec(pos[2], {0, 1, 0.5f * 2});              // (0, 1, 1)
  // (0,0,1) + 0.5 * (1,0,-1) = (0.5, 0, 0.5) -> unit length
  expectVec(nrm[0], {0.70710678f, 0, 0.70710678f});
  expectVec(nrm[1], {0, 0, 1});
}

TEST(CpuMorph, ZeroWeightsGiveTheBaseMeshAndNegativeWeightsExtrapolate) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3), nrm(3);
  const float zero[] = {0.0f, 0.0f};
  eng::morphPrimitiveCpu(p, zero, pos, nrm);
  EXPECT_EQ(pos, p.positions);
  EXPECT_EQ(nrm, p.normals);
  const float negative[] = {-1.0f, 0.0f};
  eng::morphPrimitiveCpu(p, negative, pos, nrm);
  expectVec(pos[2], {0, 1, -2});
}

TEST(CpuMorph, PositionsOnlyWhenNoNormalOutputIsGiven) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3);
  const float weights[] = {1.0f, 1.0f};
  eng::morphPrimitiveCpu(p, weights, pos, {});
  expectVec(pos[0], {4, 0, 1});
  expectVec(pos[1], {1, 4, 0});
}

TEST(CpuMorph, NormalBlendedToZeroStaysFinite) {
  eng::Primitive p = triangleWithTwoTargets();
  p.targets[0].normals[1] = {0, 0, -1};
  std::vector<glm::vec3> pos(3), nrm(3);
  const float weights[] = {1.0f, 0.0f};
  eng::morphPrimitiveCpu(p, weights, pos, nrm);
  EXPECT_TRUE(std::isfinite(nrm[1].x) && std::isfinite(nrm[1].y) && std::isfinite(nrm[1].z));
}

TEST(CpuMorphPreconditions, WeightCountMustMatchTargetCount) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3), nrm(3);
  const float one[] = {1.0f};
  try {
    eng::morphPrimitiveCpu(p, one, pos, nrm);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "morphPrimitiveCpu: 1 weights for 2 targets");
  }
}

TEST(CpuMorphPreconditions, OutputSizesMustMatchVertexCount) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> shortPos(2), pos(3), shortNrm(1);
  const float weights[] = {0.0f, 0.0f};
  EXPECT_THROW(eng::morphPrimitiveCpu(p, weights, shortPos, {}), std::invalid_argument);
  try {
    eng::morphPrimitiveCpu(p, weights, pos, shortNrm);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "morphPrimitiveCpu: outNormals has 1 entries, primitive has 3 vertices");
  }
}

}  // namespace
