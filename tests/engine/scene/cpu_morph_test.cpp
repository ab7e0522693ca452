// The CPU reference morph: base + sum(w_i * delta_i), normals renormalised.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

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

// An invalid job names the problem and leaves its outputs as they were.
void expectRefused(const eng::MorphPrimitiveJob& job, const std::string& problem) {
  const std::vector<glm::vec3> before(job.outPositions.begin(), job.outPositions.end());
  const auto found = job.Validate();
  ASSERT_FALSE(found) << "expected: " << problem;
  EXPECT_EQ(found.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_EQ(found.error().message, problem);
  EXPECT_FALSE(job.Run());
  EXPECT_TRUE(std::equal(before.begin(), before.end(), job.outPositions.begin())) << "outputs untouched";
}

TEST(CpuMorphValidity, WeightCountMustMatchTargetCount) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3, glm::vec3(7.0f)), nrm(3);
  const float one[] = {1.0f};
  expectRefused({&p, one, pos, nrm}, "MorphPrimitiveJob: 1 weights for 2 targets");
  EXPECT_FALSE(eng::morphPrimitiveCpu(p, one, pos, nrm));
}

TEST(CpuMorphValidity, OutputSizesMustMatchVertexCount) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> shortPos(2, glm::vec3(7.0f)), pos(3, glm::vec3(7.0f)), shortNrm(1);
  const float weights[] = {0.0f, 0.0f};
  expectRefused({&p, weights, shortPos, {}}, "MorphPrimitiveJob: outPositions has 2 entries, primitive has 3 vertices");
  expectRefused({&p, weights, pos, shortNrm}, "MorphPrimitiveJob: outNormals has 1 entries, primitive has 3 vertices");
}

TEST(CpuMorphValidity, NonFiniteWeightsAndMissingPrimitiveAreRefused) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3, glm::vec3(7.0f));
  const float nan[] = {0.5f, std::numeric_limits<float>::quiet_NaN()};
  expectRefused({&p, nan, pos, {}}, "MorphPrimitiveJob: weight 1 is not finite");
  const float inf[] = {std::numeric_limits<float>::infinity(), 0.0f};
  expectRefused({&p, inf, pos, {}}, "MorphPrimitiveJob: weight 0 is not finite");
  expectRefused({nullptr, {}, pos, {}}, "MorphPrimitiveJob: no primitive");
}

TEST(CpuMorphValidity, NormalsNeedAPrimitiveWithNormalsAndTargetsOfItsVertexCount) {
  eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3, glm::vec3(7.0f)), nrm(3);
  const float weights[] = {0.0f, 0.0f};
  p.normals.clear();
  expectRefused({&p, weights, pos, nrm}, "MorphPrimitiveJob: primitive has 0 normals for 3 vertices");
  p = triangleWithTwoTargets();
  p.targets[1].positions.pop_back();
  expectRefused({&p, weights, pos, {}}, "MorphPrimitiveJob: target 1 has deltas for another vertex count than 3");
}

TEST(CpuMorphValidity, AValidJobRuns) {
  const eng::Primitive p = triangleWithTwoTargets();
  std::vector<glm::vec3> pos(3), nrm(3);
  const float weights[] = {1.0f, 0.0f};
  const eng::MorphPrimitiveJob job{&p, weights, pos, nrm};
  EXPECT_TRUE(job.Validate());
  ASSERT_TRUE(job.Run());
  expectVec(pos[2], {0, 1, 2});
}

}  // namespace
