// Window loop decisions: minimised windows wait, resized ones rebuild.
#include "engine/vk/frame_pacing.h"

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

}  // namespace
