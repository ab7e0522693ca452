// Window loop decisions: minimised windows wait, resized ones rebuild.
#include "engine/vk/present/frame_pacing.h"

#include <gtest/gtest.h>

namespace {

using eng::vk::decideFrameAction;
using eng::vk::FrameAction;

TEST(FramePacing, MinimisedWindowSkipsTheFrame) {
  EXPECT_EQ(decideFrameAction({0, 0}, {800, 600}, false), FrameAction::Skip);
  EXPECT_EQ(decideFrameAction({0, 600}, {800, 600}, true), FrameAction::Skip);
  EXPECT_EQ(decideFrameAction({800, 0}, {800, 600}, false), FrameAction::Skip);
}

TEST(FramePacing, ResizedOrStaleSwapchainIsRecreated) {
  EXPECT_EQ(decideFrameAction({1024, 768}, {800, 600}, false), FrameAction::RecreateSwapchain);
  EXPECT_EQ(decideFrameAction({800, 600}, {800, 600}, true), FrameAction::RecreateSwapchain);
}

TEST(FramePacing, SteadyWindowDraws) { EXPECT_EQ(decideFrameAction({800, 600}, {800, 600}, false), FrameAction::Draw); }

using eng::vk::AdaptiveRenderScale;

// Feeds one window of identical frame times; returns whether the scale changed.
bool feedWindow(AdaptiveRenderScale& scale, double seconds) {
  bool changed = false;
  for (uint32_t i = 0; i < AdaptiveRenderScale::kWindow; ++i) changed |= scale.addFrame(seconds);
  return changed;
}

TEST(AdaptiveRenderScale, SlowFramesLowerTheScaleAsThePixelCountPredicts) {
  AdaptiveRenderScale scale(0.65f, {});
  // Twice the target: sqrt(1/2) of 0.65 is 0.46, snapped down to a step.
  EXPECT_TRUE(feedWindow(scale, 2.0 / 32.0));
  EXPECT_NEAR(scale.scale(), 0.45f, 1e-6f);
  // Never below the floor, however slow.
  EXPECT_FALSE(feedWindow(scale, 1.0));
  EXPECT_NEAR(scale.scale(), 0.45f, 1e-6f);
}

TEST(AdaptiveRenderScale, SlightlySlowFramesStepDownOnce) {
  AdaptiveRenderScale scale(0.65f, {});
  EXPECT_TRUE(feedWindow(scale, 1.1 / 32.0));
  EXPECT_NEAR(scale.scale(), 0.60f, 1e-6f);
}

TEST(AdaptiveRenderScale, FastFramesRaiseItOneStepUpToTheCeiling) {
  AdaptiveRenderScale scale(0.65f, {});
  EXPECT_TRUE(feedWindow(scale, 0.01));
  EXPECT_NEAR(scale.scale(), 0.70f, 1e-6f);
  for (int i = 0; i < 10; ++i) feedWindow(scale, 0.01);
  EXPECT_NEAR(scale.scale(), 0.90f, 1e-6f);
}

TEST(AdaptiveRenderScale, FramesNearTheTargetKeepItAndOutliersDoNotCount) {
  AdaptiveRenderScale scale(0.65f, {});
  EXPECT_FALSE(feedWindow(scale, 1.0 / 32.0));
  // Three stalls (a screenshot's read-back) among eight frames: the median is on target.
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(scale.addFrame(0.5));
  for (uint32_t i = 3; i < AdaptiveRenderScale::kWindow; ++i) EXPECT_FALSE(scale.addFrame(1.0 / 32.0));
  EXPECT_NEAR(scale.scale(), 0.65f, 1e-6f);
  // Restarted windows forget what was gathered.
  for (int i = 0; i < 7; ++i) scale.addFrame(1.0);
  scale.restart();
  EXPECT_FALSE(feedWindow(scale, 1.0 / 32.0));
  EXPECT_NEAR(scale.scale(), 0.65f, 1e-6f);
}

}  // namespace
