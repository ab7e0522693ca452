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

// ---- Tangent modes: the slopes the editor's curve view and the runtime both derive ----

TEST(KeyframeTangents, AutoIsCatmullRomFlatAtTheEndsAndAtPeaks) {
  std::vector<Keyframe> keys = {key(0, 0, KeyInterpolation::Hermite), key(1, 0.5f, KeyInterpolation::Hermite),
                                key(2, 1, KeyInterpolation::Hermite), key(3, 0.2f, KeyInterpolation::Hermite),
                                key(4, 0.4f)};
  for (Keyframe& k : keys) k.tangent = facial::TangentMode::Auto;
  facial::resolveTangents(keys);
  EXPECT_FLOAT_EQ(keys[0].outTangent, 0.0f);   // end
  EXPECT_FLOAT_EQ(keys[1].inTangent, 0.5f);    // (1 - 0) / (2 - 0)
  EXPECT_FLOAT_EQ(keys[1].outTangent, 0.5f);
  EXPECT_FLOAT_EQ(keys[2].outTangent, 0.0f);   // a peak: no overshoot above it
  EXPECT_FLOAT_EQ(keys[3].inTangent, 0.0f);    // a dip
  EXPECT_FLOAT_EQ(keys[4].inTangent, 0.0f);    // end
  // The curve never leaves the range of its keys around the peak.
  for (float t = 1.0f; t <= 3.0f; t += 0.01f) EXPECT_LE(facial::sampleKeys(keys, t), 1.0f + 1e-6f);
  // Beside a level neighbour: flat too (no dip below the level stretch).
  std::vector<Keyframe> level = {key(0, 1, KeyInterpolation::Hermite), key(1, 0, KeyInterpolation::Hermite),
                                 key(2, 0, KeyInterpolation::Hermite), key(3, 1)};
  for (Keyframe& k : level) k.tangent = facial::TangentMode::Auto;
  facial::resolveTangents(level);
  EXPECT_FLOAT_EQ(level[1].outTangent, 0.0f);
  for (float t = 0.0f; t <= 3.0f; t += 0.01f) EXPECT_GE(facial::sampleKeys(level, t), -1e-6f);
}

TEST(KeyframeTangents, SmoothFollowsOutFlatIsZeroBrokenKeepsBoth) {
  std::vector<Keyframe> keys = {key(0, 0, KeyInterpolation::Hermite, 3, 2), key(1, 1, KeyInterpolation::Hermite, 5, -1),
                                key(2, 0, KeyInterpolation::Hermite, 7, 9)};
  keys[0].tangent = facial::TangentMode::Smooth;
  keys[1].tangent = facial::TangentMode::Flat;
  keys[2].tangent = facial::TangentMode::Broken;
  facial::resolveTangents(keys);
  EXPECT_FLOAT_EQ(keys[0].inTangent, 2.0f);
  EXPECT_FLOAT_EQ(keys[0].outTangent, 2.0f);
  EXPECT_FLOAT_EQ(keys[1].inTangent, 0.0f);
  EXPECT_FLOAT_EQ(keys[1].outTangent, 0.0f);
  EXPECT_FLOAT_EQ(keys[2].inTangent, 7.0f);
  EXPECT_FLOAT_EQ(keys[2].outTangent, 9.0f);
}

TEST(KeyframeTangents, ModeNamesReadBack) {
  for (const auto& entry : facial::kTangentModeNames)
    EXPECT_EQ(facial::tangentModeFromName(facial::tangentModeName(entry.value)), entry.value);
  EXPECT_FALSE(facial::tangentModeFromName("clamped").has_value());
}
