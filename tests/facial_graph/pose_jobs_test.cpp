#include "facial/runtime/graph/pose_jobs.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

using namespace facial;

TEST(PoseJobs, LerpIsOneMinusTTimesP0PlusTTimesP1) {
  const std::vector<float> p0 = {0.0f, 1.0f, 0.5f}, p1 = {1.0f, 0.0f, 0.25f};
  std::vector<float> out(3);
  ASSERT_TRUE((LerpPoseJob{.a = p0, .b = p1, .t = 0.3f, .out = out}.Run()));
  EXPECT_FLOAT_EQ(out[0], 0.3f);
  EXPECT_FLOAT_EQ(out[1], 0.7f);
  EXPECT_FLOAT_EQ(out[2], 0.7f * 0.5f + 0.3f * 0.25f);
}

TEST(PoseJobs, BilinearMatchesTheStudyFormula) {
  // Pf = s1 (t1 Q11 + t2 Q12) + s2 (t1 Q21 + t2 Q22) with s2 = 0.25, t2 = 0.6.
  const std::vector<float> q11 = {1.0f, 0.0f}, q12 = {0.0f, 1.0f}, q21 = {0.5f, 0.5f}, q22 = {0.2f, 0.9f};
  std::vector<float> out(2);
  ASSERT_TRUE((BilinearPoseJob{.q11 = q11, .q12 = q12, .q21 = q21, .q22 = q22, .s2 = 0.25f, .t2 = 0.6f, .out = out}.Run()));
  EXPECT_FLOAT_EQ(out[0], 0.75f * (0.4f * 1.0f + 0.6f * 0.0f) + 0.25f * (0.4f * 0.5f + 0.6f * 0.2f));
  EXPECT_FLOAT_EQ(out[1], 0.75f * (0.4f * 0.0f + 0.6f * 1.0f) + 0.25f * (0.4f * 0.5f + 0.6f * 0.9f));
  // Corners reproduce the keyframes.
  ASSERT_TRUE((BilinearPoseJob{.q11 = q11, .q12 = q12, .q21 = q21, .q22 = q22, .s2 = 1.0f, .t2 = 1.0f, .out = out}.Run()));
  EXPECT_EQ(out, q22);
}

TEST(PoseJobs, AdditiveAddsMaskedLayerClampsAndCopiesLanes) {
  const std::vector<float> base = {0.9f, 0.2f, 0.5f, 0.7f /*lane*/};
  const std::vector<float> layer = {0.5f, -0.5f, 0.4f, 0.3f};
  const std::vector<float> mask = {1.0f, 1.0f, 0.0f};
  std::vector<float> out(4);
  ASSERT_TRUE((AdditivePoseJob{.base = base, .layer = layer, .mask = mask, .weight = 0.5f, .out = out}.Run()));
  EXPECT_FLOAT_EQ(out[0], 1.0f);  // 0.9 + 0.25 clamped
  EXPECT_FLOAT_EQ(out[1], 0.0f);  // 0.2 - 0.25 clamped
  EXPECT_FLOAT_EQ(out[2], 0.5f);  // masked out
  EXPECT_FLOAT_EQ(out[3], 0.7f);  // lane from base
}

TEST(PoseJobs, AccumulateAddsWeightedInput) {
  const std::vector<float> in = {0.5f, 1.0f};
  std::vector<float> out = {0.1f, 0.1f};
  ASSERT_TRUE((AccumulatePoseJob{.input = in, .weight = 0.4f, .out = out}.Run()));
  EXPECT_FLOAT_EQ(out[0], 0.3f);
  EXPECT_FLOAT_EQ(out[1], 0.5f);
}

TEST(PoseJobsValidity, MismatchedSizesAreNamedAndNothingIsWritten) {
  const std::vector<float> a(3, 1.0f), b(4, 1.0f);
  std::vector<float> out(3, 0.25f);
  const LerpPoseJob lerp{.a = a, .b = b, .t = 0.5f, .out = out};
  auto problem = lerp.Validate();
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("b has 4 entries, out has 3"), std::string::npos) << *problem;
  EXPECT_FALSE(lerp.Run());
  EXPECT_EQ(out, std::vector<float>(3, 0.25f));
  EXPECT_TRUE((LerpPoseJob{.a = a, .b = a, .t = NAN, .out = out}.Validate().has_value()));
  const std::vector<float> longMask(5, 1.0f);
  auto mask = AdditivePoseJob{.base = a, .layer = a, .mask = longMask, .out = out}.Validate();
  ASSERT_TRUE(mask.has_value());
  EXPECT_NE(mask->find("mask has 5 entries"), std::string::npos) << *mask;
  EXPECT_TRUE((BilinearPoseJob{.q11 = a, .q12 = a, .q21 = b, .q22 = a, .out = out}.Validate().has_value()));
  EXPECT_TRUE((AccumulatePoseJob{.input = b, .weight = 1.0f, .out = out}.Validate().has_value()));
}
