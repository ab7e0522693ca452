#include "facial/runtime/graph/pose_jobs.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/graph/timeline.h"
#include "tests/common/allocation_counter.h"

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
  ASSERT_FALSE(problem);
  EXPECT_EQ(problem.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_EQ(problem.error().message, "LerpPoseJob: b has 4 entries, out has 3");
  EXPECT_FALSE(lerp.Run());
  EXPECT_EQ(out, std::vector<float>(3, 0.25f));
  EXPECT_FALSE((LerpPoseJob{.a = a, .b = a, .t = NAN, .out = out}.Validate()));
  const std::vector<float> longMask(5, 1.0f);
  auto mask = AdditivePoseJob{.base = a, .layer = a, .mask = longMask, .out = out}.Validate();
  ASSERT_FALSE(mask);
  EXPECT_EQ(mask.error().message, "AdditivePoseJob: mask has 5 entries, more than out's 3");
  EXPECT_FALSE((BilinearPoseJob{.q11 = a, .q12 = a, .q21 = b, .q22 = a, .out = out}.Validate()));
  EXPECT_FALSE((AccumulatePoseJob{.input = b, .weight = 1.0f, .out = out}.Validate()));
}

// The jobs run every frame: a passing Validate() (an eng::Result<void> holding an empty
// error) must not touch the heap; only describing a failure may.
TEST(PoseJobs, ValidateAllocatesNothingOnSuccess) {
  const std::vector<float> a(64, 0.5f), mask(60, 1.0f);
  std::vector<float> out(64);
  Timeline clip;
  clip.name = "a clip name longer than any small-string buffer";
  clip.duration = 1.0f;
  clip.addTrack("jaw", std::vector<Keyframe>{{0.0f, 0.0f}, {1.0f, 1.0f}});
  const std::vector<uint32_t> channels = {3};
  std::vector<uint32_t> cursors(1, 0);
  const uint64_t before = testing_support::allocationCount();
  bool allValid = LerpPoseJob{.a = a, .b = a, .t = 0.5f, .out = out}.Validate().ok();
  allValid &= AccumulatePoseJob{.input = a, .weight = 1.0f, .out = out}.Validate().ok();
  allValid &= BilinearPoseJob{.q11 = a, .q12 = a, .q21 = a, .q22 = a, .s2 = 0.5f, .t2 = 0.5f, .out = out}.Validate().ok();
  allValid &= AdditivePoseJob{.base = a, .layer = a, .mask = mask, .out = out}.Validate().ok();
  allValid &= TimelineSampleJob{.timeline = &clip, .trackChannels = channels, .time = 0.5f, .cursors = cursors, .out = out}
                  .Validate()
                  .ok();
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
  EXPECT_TRUE(allValid);
  // The counter does count: a failure's message allocates.
  const uint64_t beforeFailure = testing_support::allocationCount();
  EXPECT_FALSE((LerpPoseJob{.a = a, .b = mask, .t = 0.5f, .out = out}.Validate()));
  EXPECT_GT(testing_support::allocationCount() - beforeFailure, 0u);
}
