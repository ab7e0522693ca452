#include "facial/runtime/graph/nodes/timeline_node.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

// Channel "a" ramps 0 -> 1 over [0, 1] s, "c" steps to 0.5 at 0.5 s; "b" has no track.
Timeline ramp() {
  Timeline t;
  t.name = "ramp";
  t.duration = 1.0f;
  t.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f}, {1.0f, 1.0f}});
  t.addTrack("c", std::vector<Keyframe>{{0.0f, 0.0f, 0, 0, KeyInterpolation::Step}, {0.5f, 0.5f}});
  return t;
}

struct TimelineRig {
  explicit TimelineRig(std::optional<LoopMode> loop) {
    GraphBuilder b(threeChannels());
    speed = b.addFloat("speed", 1.0f);
    const uint32_t clip = b.addTimeline(ramp());
    b.setRoot(b.add(TimelineNode{.timeline = clip, .loop = loop, .speed = FloatInput::bound(speed)}));
    face.emplace(instantiate(buildGraph(b)));
  }
  float a(float dt) {
    face->update(dt);
    return face->weights()[0];
  }
  ParameterIndex speed = 0;
  std::optional<GraphInstance> face;
};

}  // namespace

TEST(TimelineNode, OncePlaysThenHoldsTheLastValue) {
  TimelineRig rig(LoopMode::Once);
  EXPECT_NEAR(rig.a(0.25f), 0.25f, 1e-6f);
  EXPECT_FLOAT_EQ(rig.face->weights()[1], 0.0f);  // no track
  EXPECT_FLOAT_EQ(rig.face->weights()[2], 0.0f);  // step not reached
  EXPECT_NEAR(rig.a(0.5f), 0.75f, 1e-6f);
  EXPECT_FLOAT_EQ(rig.face->weights()[2], 0.5f);
  EXPECT_FLOAT_EQ(rig.a(3.0f), 1.0f);
}

TEST(TimelineNode, LoopWrapsAndPingPongReverses) {
  TimelineRig loop(LoopMode::Loop);
  EXPECT_NEAR(loop.a(0.75f), 0.75f, 1e-6f);
  EXPECT_NEAR(loop.a(0.5f), 0.25f, 1e-6f);
  EXPECT_NEAR(loop.a(10.0f), 0.25f, 1e-4f);
  TimelineRig pingPong(LoopMode::PingPong);
  EXPECT_NEAR(pingPong.a(0.75f), 0.75f, 1e-6f);
  EXPECT_NEAR(pingPong.a(0.5f), 0.75f, 1e-6f);  // 1.25 s: on the way back
  EXPECT_NEAR(pingPong.a(0.5f), 0.25f, 1e-6f);
  EXPECT_NEAR(pingPong.a(0.5f), 0.25f, 1e-6f);  // 2.25 s: forward again
}

TEST(TimelineNode, SpeedParameterScalesAndReversesPlayback) {
  TimelineRig rig(LoopMode::Loop);
  rig.face->setFloat(rig.speed, 2.0f);
  EXPECT_NEAR(rig.a(0.2f), 0.4f, 1e-6f);
  rig.face->setFloat(rig.speed, -1.0f);
  EXPECT_NEAR(rig.a(0.1f), 0.3f, 1e-6f);
  EXPECT_NEAR(rig.a(0.5f), 0.8f, 1e-6f);  // wrapped backward past 0
}

TEST(TimelineNode, TheTimelineDefaultsToItsOwnLoopMode) {
  TimelineRig rig(std::nullopt);  // ramp() is Once
  EXPECT_FLOAT_EQ(rig.a(5.0f), 1.0f);
}

TEST(TimelineNodeValidity, TracksMustNameChannelsOfTheGraph) {
  GraphBuilder b(threeChannels());
  Timeline t = ramp();
  t.addTrack("zz", std::vector<Keyframe>{{0.0f, 1.0f}});
  const uint32_t clip = b.addTimeline(t);
  b.setRoot(b.add(TimelineNode{.timeline = clip}));
  EXPECT_NE(buildError(b).find("/timeline: timeline 'ramp' animates 'zz', which is not a channel of this graph"),
            std::string::npos);

  GraphBuilder c(threeChannels());
  c.setRoot(c.add(TimelineNode{.timeline = 4}));
  EXPECT_NE(buildError(c).find("timeline index 4 out of range (0 timelines)"), std::string::npos);
}
