// Compaction of one mesh's weights into the active (target, weight) list.
#include "engine/vk/draw/active_weights.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace {

using eng::vk::ActiveWeight;
using eng::vk::ActiveWeightsJob;

TEST(ActiveWeights, KeepsNonZeroWeightsInTargetOrder) {
  const std::vector<float> weights{0.0f, 0.5f, 0.0f, -0.25f, 1.0f};
  std::vector<ActiveWeight> out(weights.size());
  const ActiveWeightsJob job{weights, out};
  ASSERT_TRUE(job.Validate());
  ASSERT_EQ(job.Run(), 3u);
  EXPECT_EQ(out[0].target, 1u);
  EXPECT_EQ(out[0].weight, 0.5f);
  EXPECT_EQ(out[1].target, 3u);
  EXPECT_EQ(out[1].weight, -0.25f);
  EXPECT_EQ(out[2].target, 4u);
}

TEST(ActiveWeights, SkipsWeightsBelowThreshold) {
  const std::vector<float> weights{1e-7f, -5e-7f, 2e-6f};
  std::vector<ActiveWeight> out(weights.size());
  ASSERT_EQ((ActiveWeightsJob{weights, out}.Run()), 1u);
  EXPECT_EQ(out[0].target, 2u);
}

TEST(ActiveWeights, AllZeroAndEmptyGiveNothing) {
  const std::vector<float> zeros(256, 0.0f);
  std::vector<ActiveWeight> out(zeros.size());
  EXPECT_EQ((ActiveWeightsJob{zeros, out}.Run()), 0u);
  EXPECT_EQ((ActiveWeightsJob{{}, {}}.Run()), 0u);
}

TEST(ActiveWeightsValidity, OutputTooSmallNamesSizes) {
  const std::vector<float> weights(8, 1.0f);
  std::vector<ActiveWeight> out(3);
  auto valid = ActiveWeightsJob{weights, out}.Validate();
  ASSERT_FALSE(valid);
  EXPECT_NE(valid.error().message.find("3"), std::string::npos);
  EXPECT_NE(valid.error().message.find("8"), std::string::npos);
}

TEST(ActiveWeightsValidity, NonFiniteWeightIsRejected) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const std::vector<float> weights{0.5f, bad};
    std::vector<ActiveWeight> out(2);
    auto valid = ActiveWeightsJob{weights, out}.Validate();
    ASSERT_FALSE(valid);
    EXPECT_NE(valid.error().message.find("weight 1 of 2"), std::string::npos) << valid.error().message;
  }
}

}  // namespace
