// CurveView / curve key modes: the curve view's model without ImGui, and the
// promise that the runtime plays exactly the curve the view draws.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "editor/curve_model.h"
#include "editor/timeline_document.h"
#include "facial/runtime/graph/timeline.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"

namespace {

using editor::CurveKeyMode;
using editor::CurveView;
using editor::KeyId;
using editor::TimelineDocument;
using editor::TimeWindow;

constexpr editor::CurveArea kArea{.left = 100.0f, .top = 50.0f, .width = 800.0f, .height = 316.0f};

// Hovering a key names its track, time, frame, value and mode.
TEST(CurveKeyMode, AKeysHoverTextSaysWhereItIs) {
  TimelineDocument doc("m", 2.0f);
  const size_t track = *doc.addTrack("happy");
  const KeyId onFrame = *doc.setKey(track, 1.0f, 0.75f, facial::KeyInterpolation::Cosine);
  const KeyId between = *doc.setKey(track, 1.51f, 0.25f, facial::KeyInterpolation::Step);
  EXPECT_EQ(editor::keyHoverText("happy", doc.key(onFrame)->key, 30.0f), "happy: 1.00 s (frame 30), value 0.750, cosine");
  EXPECT_EQ(editor::keyHoverText("happy", doc.key(between)->key, 24.0f), "happy: 1.51 s (frame 36.2), value 0.250, step");
  ASSERT_TRUE(editor::setCurveKeyMode(doc, onFrame, CurveKeyMode::Broken, -2.0f, 3.0f));
  EXPECT_EQ(editor::keyHoverText("AU12", doc.key(onFrame)->key, 30.0f), "AU12: 1.00 s (frame 30), value 0.750, broken");
}

// Three tracks using all seven modes, one tangent bent by hand.
TimelineDocument everyMode() {
  TimelineDocument doc("modes", 3.0f);
  const size_t a = *doc.addTrack("happy"), b = *doc.addTrack("AU26_JawDrop"), c = *doc.addTrack("browInnerUp");
  const float times[] = {0.0f, 0.4f, 0.9f, 1.3f, 1.8f, 2.2f, 2.6f, 3.0f};
  const float values[] = {0.0f, 0.8f, 0.3f, 1.0f, 0.1f, 0.6f, 0.2f, 0.9f};
  const CurveKeyMode modes[] = {CurveKeyMode::Auto,   CurveKeyMode::Smooth, CurveKeyMode::Flat,
                                CurveKeyMode::Broken, CurveKeyMode::Linear, CurveKeyMode::Step,
                                CurveKeyMode::Cosine, CurveKeyMode::Auto};
  for (size_t track : {a, b, c})
    for (size_t i = 0; i < 8; ++i) {
      const KeyId id = *doc.setKey(track, times[i], values[(i + track) % 8]);
      EXPECT_TRUE(editor::setCurveKeyMode(doc, id, modes[(i + 2 * track) % 7], -1.5f, 2.5f));
    }
  return doc;
}

TEST(CurveKeyMode, EachModeSetsItsInterpolationAndTangents) {
  TimelineDocument doc("m", 2.0f);
  const size_t track = *doc.addTrack("happy");
  ASSERT_TRUE(doc.setKey(track, 0.0f, 0.0f));
  const KeyId mid = *doc.setKey(track, 1.0f, 0.5f);
  ASSERT_TRUE(doc.setKey(track, 2.0f, 1.0f));
  for (const auto& entry : editor::kCurveKeyModeNames) {
    ASSERT_TRUE(editor::setCurveKeyMode(doc, mid, entry.value, -2.0f, 3.0f)) << entry.name;
    EXPECT_EQ(editor::curveKeyModeOf(doc.key(mid)->key), entry.value) << entry.name;
    EXPECT_EQ(editor::curveKeyModeFromName(entry.name), entry.value);
  }
  ASSERT_TRUE(editor::setCurveKeyMode(doc, mid, CurveKeyMode::Broken, -2.0f, 3.0f));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.inTangent, -2.0f);
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 3.0f);
  ASSERT_TRUE(editor::setCurveKeyMode(doc, mid, CurveKeyMode::Smooth, {}, 1.25f));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.inTangent, 1.25f);
  ASSERT_TRUE(editor::setCurveKeyMode(doc, mid, CurveKeyMode::Flat));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 0.0f);
  ASSERT_TRUE(editor::setCurveKeyMode(doc, mid, CurveKeyMode::Auto));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 0.5f);
  // Each is one undo step.
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(editor::curveKeyModeOf(doc.key(mid)->key), CurveKeyMode::Flat);
  EXPECT_FALSE(editor::setCurveKeyMode(doc, 9999, CurveKeyMode::Auto));
  EXPECT_FALSE(editor::setCurveKeyMode(doc, mid, CurveKeyMode::Broken, NAN, 0.0f));
}

TEST(CurveView, TheRuntimePlaysExactlyTheCurveTheViewDraws) {
  TimelineDocument doc = everyMode();
  const std::filesystem::path file = testing_support::freshTempDir("curve_view_runtime") / "modes.json";
  ASSERT_TRUE(doc.save(file));
  auto timeline = facial::loadTimeline(file);  // through the file, as the runtime gets it
  ASSERT_TRUE(timeline.ok()) << timeline.error().message;
  ASSERT_EQ(timeline->tracks.size(), doc.tracks().size());

  const CurveView view = CurveView::fit(kArea, {.start = -0.2f, .end = 3.2f}, 0.0f, 1.0f);
  std::vector<uint32_t> channels(doc.tracks().size()), cursors(doc.tracks().size(), 0);
  for (size_t i = 0; i < channels.size(); ++i) channels[i] = uint32_t(i);
  std::vector<float> pose(channels.size());
  size_t compared = 0;
  for (size_t track = 0; track < doc.tracks().size(); ++track) {
    const auto samples = view.curveSamples(doc.tracks()[track].keys);
    ASSERT_GT(samples.size(), 400u);  // every 2 px of 800
    for (const glm::vec2 s : samples) {
      const facial::TimelineSampleJob job{.timeline = &*timeline, .trackChannels = channels, .time = s.x,
                                          .cursors = cursors, .out = pose};
      ASSERT_TRUE(job.Run());
      EXPECT_EQ(pose[track], s.y) << doc.tracks()[track].channel << " at " << s.x;  // bit for bit
      EXPECT_EQ(doc.sample(track, s.x), s.y);
      ++compared;
    }
  }
  EXPECT_GT(compared, 1200u);
}

TEST(CurveView, SamplesIncludeEveryKeyTimeInOrder) {
  TimelineDocument doc = everyMode();
  const CurveView view = CurveView::fit(kArea, {.start = 0.0f, .end = 3.0f}, 0.0f, 1.0f);
  const auto samples = view.curveSamples(doc.tracks()[0].keys);
  for (size_t i = 1; i < samples.size(); ++i) EXPECT_LE(samples[i - 1].x, samples[i].x);
  for (const editor::DocumentKey& k : doc.tracks()[0].keys) {
    bool found = false;
    for (const glm::vec2 s : samples) found = found || (s.x == k.key.time && s.y == k.key.value);
    EXPECT_TRUE(found) << "key at " << k.key.time;
  }
}

TEST(CurveView, MapsTimeAndValueAndBack) {
  const CurveView view = CurveView::fit(kArea, {.start = 1.0f, .end = 3.0f}, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(view.xAt(1.0f), 100.0f);
  EXPECT_FLOAT_EQ(view.xAt(3.0f), 900.0f);
  EXPECT_FLOAT_EQ(view.yAt(0.0f), 50.0f + 316.0f - CurveView::kValueMargin);
  EXPECT_FLOAT_EQ(view.yAt(1.0f), 50.0f + CurveView::kValueMargin);
  EXPECT_FLOAT_EQ(view.timeAt(view.xAt(2.25f)), 2.25f);
  EXPECT_NEAR(view.valueAt(view.yAt(0.3f)), 0.3f, 1e-6f);
}

TEST(CurveView, HandlesLieAlongTheSlopesAndADragSetsThem) {
  TimelineDocument doc("h", 2.0f);
  const size_t track = *doc.addTrack("happy");
  ASSERT_TRUE(doc.setKey(track, 0.0f, 0.0f, facial::KeyInterpolation::Hermite));
  const KeyId mid = *doc.setKey(track, 1.0f, 0.5f, facial::KeyInterpolation::Hermite);
  ASSERT_TRUE(doc.setKey(track, 2.0f, 1.0f));
  const CurveView view = CurveView::fit({.left = 0.0f, .top = 0.0f, .width = 400.0f, .height = 216.0f},
                                        {.start = 0.0f, .end = 2.0f}, 0.0f, 1.0f);
  // 200 px/s and 200 px per unit of value: slope 0.5 is 0.5 px up per px right.
  const facial::Keyframe k = doc.key(mid)->key;  // a copy: edits below replace the document's keys
  const glm::vec2 out = view.outHandle(k), in = view.inHandle(k), at = view.pixelOf(k);
  EXPECT_NEAR(glm::length(out - at), CurveView::kHandleLength, 1e-3f);
  EXPECT_NEAR((at.y - out.y) / (out.x - at.x), 0.5f, 1e-5f);
  EXPECT_NEAR(in.x - at.x, at.x - out.x, 1e-4f);
  // A click takes the handle of a selected key, the key otherwise.
  doc.select(mid);
  auto hit = view.hitAt(doc, std::vector<size_t>{track}, out + glm::vec2(1.0f, 0.0f));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->part, CurveView::Part::OutHandle);
  EXPECT_EQ(view.hitAt(doc, std::vector<size_t>{track}, at)->part, CurveView::Part::Key);
  EXPECT_FALSE(view.hitAt(doc, std::vector<size_t>{track}, at + glm::vec2(0.0f, 60.0f)).has_value());
  // Dragging the out handle 40 px right and level flattens it: the key turns smooth, both sides follow.
  const float slope = view.slopeToward(k, at + glm::vec2(40.0f, 0.0f), false);
  EXPECT_FLOAT_EQ(slope, 0.0f);
  doc.beginMove();
  ASSERT_TRUE(doc.dragTangent(mid, slope, view.slopeToward(k, at + glm::vec2(30.0f, -30.0f), false), false));
  doc.endMove();
  EXPECT_EQ(editor::curveKeyModeOf(doc.key(mid)->key), CurveKeyMode::Smooth);
  EXPECT_FLOAT_EQ(doc.key(mid)->key.inTangent, 1.0f);
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 1.0f);
  ASSERT_TRUE(doc.undo());  // one step
  EXPECT_EQ(editor::curveKeyModeOf(doc.key(mid)->key), CurveKeyMode::Auto);
  // Alt breaks it: each side its own slope.
  doc.beginMove();
  ASSERT_TRUE(doc.dragTangent(mid, -1.0f, 2.0f, true));
  doc.endMove();
  EXPECT_EQ(editor::curveKeyModeOf(doc.key(mid)->key), CurveKeyMode::Broken);
  EXPECT_FLOAT_EQ(doc.key(mid)->key.inTangent, -1.0f);
  // A handle pulled across its key stays on its side (no reversed tangent).
  EXPECT_TRUE(std::isfinite(view.slopeToward(k, at + glm::vec2(-5.0f, -10.0f), false)));
  EXPECT_GT(view.slopeToward(k, at + glm::vec2(-5.0f, -10.0f), false), 0.0f);
}

TEST(CurveView, ColoursDifferForOverlaidTracks) {
  EXPECT_NE(editor::curveColour(0), editor::curveColour(1));
  EXPECT_EQ(editor::curveColour(0), editor::curveColour(8));
}

}  // namespace
