#include "facial/runtime/graph/timeline.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

using namespace facial;

namespace {

Timeline twoTracks() {
  Timeline t;
  t.name = "clip";
  t.duration = 2.0f;
  const std::vector<Keyframe> jaw = {{0.0f, 0.0f}, {1.0f, 1.0f}, {2.0f, 0.0f}};
  const std::vector<Keyframe> brow = {{0.5f, 0.2f, 0, 0, KeyInterpolation::Step}, {1.5f, 0.6f}};
  t.addTrack("jaw", jaw);
  t.addTrack("brow", brow);
  return t;
}

}  // namespace

TEST(Timeline, ClipTimeFollowsTheLoopMode) {
  EXPECT_FLOAT_EQ(clipTime(LoopMode::Once, 2.0f, 3.5f), 2.0f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::Once, 2.0f, -1.0f), 0.0f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::Loop, 2.0f, 3.5f), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::Loop, 2.0f, -0.5f), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::PingPong, 2.0f, 1.5f), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::PingPong, 2.0f, 2.5f), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(LoopMode::PingPong, 2.0f, 4.25f), 0.25f);
}

TEST(Timeline, TracksKeepTheirKeysInOneFlatArray) {
  const Timeline t = twoTracks();
  ASSERT_EQ(t.keys.size(), 5u);
  EXPECT_EQ(t.trackKeys(1).size(), 2u);
  EXPECT_FLOAT_EQ(t.trackKeys(1)[0].value, 0.2f);
  EXPECT_EQ(t.findTrack("brow"), &t.tracks[1]);
  EXPECT_EQ(t.findTrack("nose"), nullptr);
  EXPECT_FLOAT_EQ(t.lastKeyTime(), 2.0f);
}

TEST(Timeline, SampleJobWritesEachTrackIntoItsChannel) {
  const Timeline t = twoTracks();
  const std::vector<uint32_t> channels = {2, 0};
  std::vector<uint32_t> cursors(2, 0);
  std::vector<float> pose(4, -1.0f);
  ASSERT_TRUE((TimelineSampleJob{.timeline = &t, .trackChannels = channels, .time = 0.75f, .cursors = cursors, .out = pose}.Run()));
  EXPECT_FLOAT_EQ(pose[2], 0.75f);  // jaw, linear
  EXPECT_FLOAT_EQ(pose[0], 0.2f);   // brow, step
  EXPECT_FLOAT_EQ(pose[1], -1.0f);  // untouched
}

TEST(TimelineValidity, ProblemsNameTheTrack) {
  Timeline t = twoTracks();
  EXPECT_TRUE(t.validate());
  t.duration = 1.0f;
  auto late = t.validate();
  ASSERT_FALSE(late);
  EXPECT_EQ(late.error().kind, eng::ErrorKind::Malformed);
  EXPECT_NE(late.error().message.find("track 0 ('jaw')"), std::string::npos) << late.error().message;
  t = twoTracks();
  t.addTrack("jaw", std::vector<Keyframe>{{0.0f, 0.0f}});
  ASSERT_FALSE(t.validate());
  EXPECT_NE(t.validate().error().message.find("same channel as track 0"), std::string::npos);
  t = twoTracks();
  t.duration = NAN;
  EXPECT_FALSE(t.validate());
  t = twoTracks();
  t.tracks[1].keyCount = 9;
  ASSERT_FALSE(t.validate());
  EXPECT_NE(t.validate().error().message.find("run past"), std::string::npos);
}

TEST(TimelineValidity, SampleJobNamesMismatchedCounts) {
  const Timeline t = twoTracks();
  const std::vector<uint32_t> channels = {0};
  std::vector<uint32_t> cursors(2, 0);
  std::vector<float> pose(4);
  auto problem = TimelineSampleJob{.timeline = &t, .trackChannels = channels, .cursors = cursors, .out = pose}.Validate();
  ASSERT_FALSE(problem);
  EXPECT_EQ(problem.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_NE(problem.error().message.find("2 tracks, 1 channel indices and 2 cursors"), std::string::npos)
      << problem.error().message;
  const std::vector<uint32_t> outside = {0, 9};
  EXPECT_FALSE((TimelineSampleJob{.timeline = &t, .trackChannels = outside, .cursors = cursors, .out = pose}.Validate()));
}
