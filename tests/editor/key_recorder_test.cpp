// editor/key_recorder.h: a recorded gesture becomes a few keys per second
// that stay within the tolerance of every frame, only for the channels that
// moved, written into the timeline document over what was there.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "editor/key_recorder.h"
#include "editor/timeline_document.h"

namespace {

using editor::KeyRecorder;

float linearAt(const std::vector<facial::Keyframe>& keys, float time) {
  for (size_t i = 1; i < keys.size(); ++i)
    if (time <= keys[i].time) {
      const float u = (time - keys[i - 1].time) / (keys[i].time - keys[i - 1].time);
      return keys[i - 1].value + u * (keys[i].value - keys[i - 1].value);
    }
  return keys.back().value;
}

// Two seconds at 60 frames a second: a smooth swing on channel "a", "b" held still.
KeyRecorder recordSwing(float startTime, KeyRecorder::Options options = {}) {
  KeyRecorder recorder(options);
  recorder.start({"a", "b"}, startTime);
  for (int frame = 0; frame <= 120; ++frame) {
    const float t = float(frame) / 60.0f;
    const float values[2] = {0.5f + 0.4f * std::sin(3.0f * t), 0.25f};
    recorder.sample(t, values);
  }
  return recorder;
}

}  // namespace

TEST(KeyRecorder, SimplifyKeepsEndsAndTheSamplesThatBend) {
  const std::vector<float> times = {0, 1, 2, 3, 4}, line = {0, 0.25f, 0.5f, 0.75f, 1}, corner = {0, 0.5f, 1, 0.5f, 0};
  EXPECT_EQ(KeyRecorder::simplify(times, line, 0.01f), (std::vector<size_t>{0, 4}));
  EXPECT_EQ(KeyRecorder::simplify(times, corner, 0.01f), (std::vector<size_t>{0, 2, 4}));
  EXPECT_EQ(KeyRecorder::simplify({times.data(), 1}, {line.data(), 1}, 0.01f), (std::vector<size_t>{0}));
}

TEST(KeyRecorder, AGestureBecomesAFewKeysWithinTolerance) {
  KeyRecorder recorder = recordSwing(0.5f);
  EXPECT_EQ(recorder.sampleCount(), 121u);
  const auto tracks = recorder.stop();
  ASSERT_EQ(tracks.size(), 1u) << "the still channel is left out";
  EXPECT_EQ(tracks[0].channel, "a");
  const auto& keys = tracks[0].keys;
  EXPECT_GE(keys.size(), 4u);
  EXPECT_LE(keys.size(), 13u) << "at most 6 keys a second over 2 s";
  EXPECT_FLOAT_EQ(keys.front().time, 0.5f);
  EXPECT_FLOAT_EQ(keys.back().time, 2.5f);
  float worst = 0.0f;
  for (int frame = 0; frame <= 120; ++frame) {
    const float t = float(frame) / 60.0f;
    worst = std::max(worst, std::abs(linearAt(keys, 0.5f + t) - (0.5f + 0.4f * std::sin(3.0f * t))));
  }
  // Within 0.01 would take more than 6 keys a second for this swing: the tolerance was raised to fit.
  EXPECT_GT(tracks[0].tolerance, 0.01f);
  EXPECT_LE(tracks[0].tolerance, 0.04f);
  EXPECT_LE(worst, tracks[0].tolerance + 1e-5f);
  std::printf("2 s swing at 60 fps: %zu keys, within %.4f (tolerance %.2f)\n", keys.size(), worst, tracks[0].tolerance);
}

TEST(KeyRecorder, ASlowGestureStaysWithinTheAskedTolerance) {
  KeyRecorder recorder;
  recorder.start({"a"}, 0.0f);
  for (int frame = 0; frame <= 120; ++frame) {
    const float t = float(frame) / 60.0f, value = 0.5f + 0.3f * std::sin(1.0f * t);
    recorder.sample(t, {&value, 1});
  }
  const auto tracks = recorder.stop();
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_FLOAT_EQ(tracks[0].tolerance, 0.01f);
  EXPECT_LE(tracks[0].keys.size(), 13u);
  for (int frame = 0; frame <= 120; ++frame) {
    const float t = float(frame) / 60.0f;
    EXPECT_LE(std::abs(linearAt(tracks[0].keys, t) - (0.5f + 0.3f * std::sin(t))), 0.01f + 1e-5f) << t;
  }
}

TEST(KeyRecorder, ATightToleranceIsLoosenedToTheKeyRate) {
  KeyRecorder recorder = recordSwing(0.0f, {.tolerance = 1e-6f, .maxKeysPerSecond = 3.0f});
  const auto tracks = recorder.stop();
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_LE(tracks[0].keys.size(), 7u);
}

TEST(KeyRecorder, SkipsFramesThatCannotBeKeys) {
  KeyRecorder recorder;
  recorder.start({"a"}, 0.0f);
  const float one = 1.0f, nan = NAN, two[2] = {0, 0};
  recorder.sample(0.0f, {&one, 1});
  recorder.sample(0.0f, {&one, 1});      // the same time again
  recorder.sample(0.1f, {&nan, 1});      // not finite
  recorder.sample(0.2f, {two, 2});       // the wrong count
  recorder.sample(NAN, {&one, 1});
  EXPECT_EQ(recorder.sampleCount(), 1u);
  EXPECT_TRUE(recorder.stop().empty());
  EXPECT_FALSE(recorder.recording());
}

TEST(KeyRecorder, WritesKeysOverTheRecordedSpanAndLengthensTheClip) {
  editor::TimelineDocument doc("clip", 2.0f);
  const size_t a = doc.addTrack("a").value();
  ASSERT_TRUE(doc.setKey(a, 1.0f, 0.9f).ok());   // inside the recorded span: replaced
  ASSERT_TRUE(doc.setKey(a, 0.2f, 0.1f).ok());   // before it: kept
  KeyRecorder recorder = recordSwing(0.5f);
  const size_t samples = recorder.sampleCount();
  const auto tracks = recorder.stop();
  auto written = editor::writeRecording(doc, tracks, samples);
  ASSERT_TRUE(written.ok()) << written.error().message;
  EXPECT_EQ(written->tracks, 1u);
  EXPECT_EQ(written->keys, tracks[0].keys.size());
  EXPECT_EQ(written->samples, 121u);
  EXPECT_FLOAT_EQ(written->seconds, 2.0f);
  EXPECT_FLOAT_EQ(doc.duration(), 2.5f);
  ASSERT_EQ(doc.tracks()[a].keys.size(), tracks[0].keys.size() + 1);
  EXPECT_FLOAT_EQ(doc.tracks()[a].keys[0].key.value, 0.1f);
  EXPECT_NEAR(doc.sample(a, 1.0f), linearAt(tracks[0].keys, 1.0f), 1e-5f);
}

TEST(KeyRecorder, TheWholeTakeIsOneUndoStep) {
  editor::TimelineDocument doc("clip", 2.0f);
  const size_t a = doc.addTrack("a").value();
  ASSERT_TRUE(doc.setKey(a, 1.0f, 0.9f).ok());
  const std::string before = std::string(doc.undoLabel());
  KeyRecorder recorder = recordSwing(0.5f);
  const size_t samples = recorder.sampleCount();
  ASSERT_TRUE(editor::writeRecording(doc, recorder.stop(), samples).ok());
  EXPECT_EQ(doc.undoLabel(), "record");
  EXPECT_GT(doc.tracks()[a].keys.size(), 2u);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.undoLabel(), before) << "one step took the keys, the deleted key and the longer clip back";
  ASSERT_EQ(doc.tracks()[a].keys.size(), 1u);
  EXPECT_FLOAT_EQ(doc.tracks()[a].keys[0].key.value, 0.9f);
  EXPECT_FLOAT_EQ(doc.duration(), 2.0f);
  ASSERT_TRUE(doc.redo());
  EXPECT_FLOAT_EQ(doc.duration(), 2.5f);
}
