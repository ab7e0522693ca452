#include "facial/runtime/graph/nodes/blink_node.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

const uint32_t kBlinkL = *actionUnitIndex("AU45_Blink_L");
const uint32_t kBlinkR = *actionUnitIndex("AU45_Blink_R");
const uint32_t kLidRaiser = *actionUnitIndex("AU5_UpperLidRaiser");

// blink(pose) over the action units; the pose's AU weights and blink override under test.
GraphInstance blinking(std::vector<std::pair<uint32_t, float>> base, VrmOverride overrideBlink = VrmOverride::None,
                       uint64_t seed = 0, float scale = 1.0f) {
  GraphBuilder b(ChannelSet::actionUnits());
  std::vector<float> weights(actionUnits().size(), 0.0f);
  for (auto [channel, w] : base) weights[channel] = w;
  const NodeIndex pose = b.add(PoseNode{.weights = weights, .scale = FloatInput::fixed(scale), .overrideBlink = overrideBlink});
  b.setRoot(b.add(BlinkNode{.input = pose}));
  return instantiate(buildGraph(b), seed);
}

// Blink channel L over `seconds` at step dt.
std::vector<float> record(GraphInstance& face, float seconds, float dt) {
  std::vector<float> out;
  for (float t = 0.0f; t < seconds; t += dt) {
    face.update(dt);
    out.push_back(face.weights()[kBlinkL]);
    EXPECT_EQ(face.weights()[kBlinkL], face.weights()[kBlinkR]);
  }
  return out;
}

// Times (s) at which the channel rises above `threshold` from below.
std::vector<float> onsets(const std::vector<float>& track, float dt, float threshold) {
  std::vector<float> out;
  for (size_t i = 1; i < track.size(); ++i)
    if (track[i - 1] <= threshold && track[i] > threshold) out.push_back(static_cast<float>(i) * dt);
  return out;
}

}  // namespace

TEST(BlinkNode, IntervalsAreNaturalAndDoubleBlinksOccasional) {
  GraphInstance face = blinking({});
  const float dt = 1.0f / 240.0f;
  const std::vector<float> starts = onsets(record(face, 900.0f, dt), dt, 0.0f);
  const BlinkNode defaults;
  const float blink = defaults.closeDuration + defaults.closedDuration + defaults.openDuration;  // 0.18 s
  int doubles = 0, singles = 0;
  bool previousWasDouble = false;
  float sum = 0.0f;
  for (size_t i = 1; i < starts.size(); ++i) {
    const float gap = starts[i] - starts[i - 1];
    if (std::abs(gap - (blink + defaults.doubleBlinkGap)) < 2 * dt) {
      ++doubles;
      EXPECT_FALSE(previousWasDouble) << "a triple blink at " << starts[i];
      previousWasDouble = true;
      continue;
    }
    previousWasDouble = false;
    ++singles;
    sum += gap;
    EXPECT_GE(gap, blink + defaults.minInterval - 2 * dt) << "at " << starts[i];
    EXPECT_LE(gap, blink + defaults.maxInterval + 2 * dt) << "at " << starts[i];
  }
  ASSERT_GT(singles, 150);
  EXPECT_NEAR(sum / singles, blink + 0.5f * (defaults.minInterval + defaults.maxInterval), 0.3f);  // uniform mean
  const float doubleShare = static_cast<float>(doubles) / static_cast<float>(singles + doubles);
  EXPECT_GT(doubleShare, 0.03f);
  EXPECT_LT(doubleShare, 0.2f);
}

TEST(BlinkNode, LidsCloseFasterThanTheyOpen) {
  GraphInstance face = blinking({});
  const float dt = 1e-3f;
  const std::vector<float> track = record(face, 8.0f, dt);
  const size_t start = static_cast<size_t>(onsets(track, dt, 0.0f).front() / dt);
  size_t closed = start, reopened = start;
  while (track[closed] < 1.0f) ++closed;
  while (track[reopened + 1] > 0.0f) ++reopened;
  const BlinkNode defaults;
  EXPECT_NEAR((closed - start + 1) * dt, defaults.closeDuration, 3 * dt);
  EXPECT_NEAR((reopened - start + 1) * dt, defaults.closeDuration + defaults.closedDuration + defaults.openDuration, 3 * dt);
  // Cosine-eased phases: no step between frames larger than the curve's peak rate allows.
  for (size_t i = start; i <= reopened; ++i) EXPECT_LE(std::abs(track[i + 1] - track[i]), defaults.maxRate() * dt + 1e-5f);
}

TEST(BlinkNode, ABlinkClosesTheLidFullyFromWhereTheExpressionHoldsIt) {
  GraphInstance face = blinking({{kBlinkL, 0.4f}, {kBlinkR, 0.4f}});
  const std::vector<float> track = record(face, 10.0f, 1e-3f);
  EXPECT_FLOAT_EQ(*std::min_element(track.begin(), track.end()), 0.4f);
  EXPECT_FLOAT_EQ(*std::max_element(track.begin(), track.end()), 1.0f);
}

TEST(BlinkNode, WideEyesSuppressBlinking) {
  GraphInstance wide = blinking({{kLidRaiser, 1.0f}});
  const std::vector<float> none = record(wide, 30.0f, 1.0f / 120);
  EXPECT_FLOAT_EQ(*std::max_element(none.begin(), none.end()), 0.0f);
  // AU5 = 0.6 sits mid-way through the suppression ramp: smoothstep(0.35, 0.85, 0.6) = 0.5.
  GraphInstance half = blinking({{kLidRaiser, 0.6f}});
  const std::vector<float> partial = record(half, 30.0f, 1e-3f);
  EXPECT_NEAR(*std::max_element(partial.begin(), partial.end()), 0.5f, 1e-4f);
}

TEST(BlinkNode, VrmOverrideBlockStopsAndBlendScalesBlinking) {
  GraphInstance blocked = blinking({}, VrmOverride::Block);
  const std::vector<float> b = record(blocked, 30.0f, 1.0f / 120);
  EXPECT_FLOAT_EQ(*std::max_element(b.begin(), b.end()), 0.0f);
  // "blend" shown at 40%: blinking scaled by 1 - 0.4.
  GraphInstance blended = blinking({}, VrmOverride::Blend, 0, 0.4f);
  const std::vector<float> s = record(blended, 30.0f, 1e-3f);
  EXPECT_NEAR(*std::max_element(s.begin(), s.end()), 0.6f, 1e-4f);
}

TEST(BlinkNode, SameSeedSameBlinksOtherSeedOtherBlinks) {
  GraphInstance a = blinking({}, VrmOverride::None, 42), b = blinking({}, VrmOverride::None, 42);
  GraphInstance c = blinking({}, VrmOverride::None, 43);
  const std::vector<float> ta = record(a, 60.0f, 1.0f / 60), tb = record(b, 60.0f, 1.0f / 60), tc = record(c, 60.0f, 1.0f / 60);
  EXPECT_EQ(ta, tb);
  EXPECT_NE(ta, tc);
}

TEST(BlinkNodeValidity, NeedsBlinkChannelsAndSaneTimings) {
  GraphBuilder noBlink(threeChannels());
  noBlink.setRoot(noBlink.add(BlinkNode{.input = addPose(noBlink, {0, 0, 0})}));
  EXPECT_NE(buildError(noBlink).find("/channels: no blink channels"), std::string::npos);

  GraphBuilder named(threeChannels());
  named.setRoot(named.add(BlinkNode{.input = addPose(named, {0, 0, 0}), .channels = {"a", "eyeBlink_L"}}));
  EXPECT_NE(buildError(named).find("/channels/1: 'eyeBlink_L' is not a channel"), std::string::npos);

  GraphBuilder order(ChannelSet::actionUnits());
  order.setRoot(order.add(BlinkNode{.input = addPose(order, std::vector<float>(actionUnits().size(), 0.0f)),
                                    .minInterval = 5.0f, .maxInterval = 3.0f}));
  EXPECT_NE(buildError(order).find("/maxInterval: is shorter than minInterval"), std::string::npos);

  GraphBuilder raw(threeChannels());
  raw.setRoot(raw.add(BlinkNode{.input = addPose(raw, {0, 0, 0}), .channels = {"a", "b"}, .wideChannels = {"c"}}));
  EXPECT_TRUE(raw.build().ok());
}
