#include "facial/runtime/curves/keyframe.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

using facial::Keyframe;
using facial::KeyInterpolation;

namespace {

Keyframe key(float t, float v, KeyInterpolation i = KeyInterpolation::Linear, float in = 0, float out = 0) {
  return Keyframe{t, v, in, out, i};
}

}  // namespace

TEST(Keyframe, StepHoldsTheFirstValueUntilTheNextKey) {
  const Keyframe k0 = key(1, 0.2f, KeyInterpolation::Step), k1 = key(3, 0.8f);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 1.0f), 0.2f);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 2.999f), 0.2f);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 3.0f), 0.8f);
}

TEST(Keyframe, LinearIsTheStraightLine) {
  const Keyframe k0 = key(1, 0.2f), k1 = key(3, 0.8f);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 1.5f), 0.2f + 0.6f * 0.25f);
  EXPECT_FLOAT_EQ(facial::segmentDerivative(k0, k1, 2.0f), 0.3f);
}

TEST(Keyframe, CosineFollowsOneMinusCosOverTwo) {
  const Keyframe k0 = key(0, 1.0f, KeyInterpolation::Cosine), k1 = key(2, 0.0f);
  for (float s : {0.0f, 0.1f, 0.25f, 0.5f, 0.9f, 1.0f}) {
    const float expected = 1.0f - (1.0f - std::cos(std::numbers::pi_v<float> * s)) / 2.0f;
    EXPECT_NEAR(facial::interpolateSegment(k0, k1, 2.0f * s), expected, 1e-6f) << "s=" << s;
  }
  // Peak speed at the middle: |dv/dt| = (pi/2) * |dv| / length.
  EXPECT_NEAR(facial::segmentDerivative(k0, k1, 1.0f), -std::numbers::pi_v<float> / 4.0f, 1e-5f);
}

TEST(Keyframe, HermiteMatchesValuesAndTangentsAtBothEnds) {
  const Keyframe k0 = key(1, 0.5f, KeyInterpolation::Hermite, 0, 2.0f);
  const Keyframe k1 = key(1.5f, 0.1f, KeyInterpolation::Linear, -1.0f, 0);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(facial::interpolateSegment(k0, k1, 1.5f), 0.1f);
  EXPECT_NEAR(facial::segmentDerivative(k0, k1, 1.0f), 2.0f, 1e-5f);
  EXPECT_NEAR(facial::segmentDerivative(k0, k1, 1.5f), -1.0f, 1e-5f);
  // Midpoint from the basis: (v0 + v1)/2 + L (m0 - m1)/8.
  EXPECT_NEAR(facial::interpolateSegment(k0, k1, 1.25f), 0.3f + 0.5f * (2.0f + 1.0f) / 8.0f, 1e-6f);
}

TEST(Keyframe, SamplingHoldsTheEndValuesOutsideTheKeys) {
  const std::vector<Keyframe> keys = {key(1, 0.3f), key(2, 0.9f)};
  EXPECT_FLOAT_EQ(facial::sampleKeys(keys, -5.0f), 0.3f);
  EXPECT_FLOAT_EQ(facial::sampleKeys(keys, 7.0f), 0.9f);
  const std::vector<Keyframe> single = {key(0.5f, 0.4f)};
  EXPECT_FLOAT_EQ(facial::sampleKeys(single, 3.0f), 0.4f);
}

TEST(Keyframe, CursorAgreesWithBinarySearchForwardBackwardAndSeeks) {
  std::vector<Keyframe> keys;
  for (int i = 0; i < 50; ++i) keys.push_back(key(0.1f * i + 0.01f * (i % 3), std::sin(0.3f * i)));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> anywhere(-1.0f, 6.0f);
  uint32_t cursor = 0;
  float time = 0.0f;
  for (int step = 0; step < 2000; ++step) {
    if (step % 50 == 49) time = anywhere(rng);    // seek
    else if (step % 7 == 0) time -= 0.05f;        // small step back
    else time += 0.013f;                          // playback
    const float expected = facial::sampleKeys(keys, time);
    EXPECT_FLOAT_EQ(facial::sampleKeys(keys, time, cursor), expected) << "time " << time;
    EXPECT_EQ(facial::findSegment(keys, time), facial::findSegment(keys, time, cursor));
  }
}

TEST(Keyframe, ForwardPlaybackMovesTheCursorOneSegmentAtATime) {
  std::vector<Keyframe> keys;
  for (int i = 0; i < 10; ++i) keys.push_back(key(float(i), float(i)));
  uint32_t cursor = 0;
  for (float t = 0.0f; t < 8.9f; t += 0.25f) {
    const uint32_t before = cursor;
    (void)facial::sampleKeys(keys, t, cursor);
    EXPECT_LE(cursor - before, 1u);
    EXPECT_EQ(cursor, static_cast<uint32_t>(t));
  }
}

TEST(KeyframeValidity, RejectsUnsortedDuplicateNonFiniteAndEmpty) {
  EXPECT_FALSE(facial::validateKeys(std::vector<Keyframe>{}));
  auto unsorted = facial::validateKeys(std::vector<Keyframe>{key(1, 0), key(0.5f, 1)});
  ASSERT_FALSE(unsorted);
  EXPECT_EQ(unsorted.error().kind, eng::ErrorKind::Malformed);
  EXPECT_NE(unsorted.error().message.find("key 1"), std::string::npos) << unsorted.error().message;
  EXPECT_FALSE(facial::validateKeys(std::vector<Keyframe>{key(1, 0), key(1, 1)}));
  EXPECT_FALSE(facial::validateKeys(std::vector<Keyframe>{key(0, NAN)}));
  EXPECT_TRUE(facial::validateKeys(std::vector<Keyframe>{key(0, 0), key(1, 1)}));
}

TEST(KeyframeValidity, InterpolationNamesRoundTrip) {
  for (auto k : {KeyInterpolation::Step, KeyInterpolation::Linear, KeyInterpolation::Cosine, KeyInterpolation::Hermite})
    EXPECT_EQ(facial::keyInterpolationFromName(facial::keyInterpolationName(k)), k);
  EXPECT_FALSE(facial::keyInterpolationFromName("bezier").has_value());
}
