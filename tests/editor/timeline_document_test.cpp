// TimelineDocument: the timeline editor's model (sorted keys, moves, undo,
// files). No UI involved.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "editor/timeline_document.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using editor::KeyId;
using editor::TimelineDocument;
using facial::KeyInterpolation;

std::vector<float> times(const TimelineDocument& doc, size_t track) {
  std::vector<float> out;
  for (const auto& k : doc.tracks()[track].keys) out.push_back(k.key.time);
  return out;
}

bool sorted(const TimelineDocument& doc) {
  for (const auto& track : doc.tracks())
    for (size_t i = 1; i < track.keys.size(); ++i)
      if (!(track.keys[i].key.time - track.keys[i - 1].key.time >= TimelineDocument::kMinKeySpacing)) return false;
  return true;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(TimelineDocument, KeysAddedInAnyOrderStaySorted) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU26_JawDrop");
  for (float t : {1.5f, 0.2f, 0.9f, 0.0f, 2.0f}) ASSERT_TRUE(doc.setKey(track, t, t / 2.0f));
  EXPECT_EQ(times(doc, track), (std::vector<float>{0.0f, 0.2f, 0.9f, 1.5f, 2.0f}));
  EXPECT_NEAR(doc.sample(track, 1.2f), 0.6f, 1e-5f);  // linear between (0.9, .45) and (1.5, .75)
}

TEST(TimelineDocument, KeyOnAnExistingTimeReplacesItsValue) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU12");
  const KeyId a = *doc.setKey(track, 0.5f, 0.2f);
  const KeyId b = *doc.setKey(track, 0.5f + 0.2f * TimelineDocument::kMinKeySpacing, 0.8f, KeyInterpolation::Step);
  EXPECT_EQ(a, b);
  ASSERT_EQ(doc.tracks()[track].keys.size(), 1u);
  EXPECT_FLOAT_EQ(doc.tracks()[track].keys[0].key.value, 0.8f);
  EXPECT_EQ(doc.tracks()[track].keys[0].key.interpolation, KeyInterpolation::Step);
}

TEST(TimelineDocument, ValuesAndTimesAreClampedIntoRange) {
  TimelineDocument doc("t", 1.0f);
  const size_t track = *doc.addTrack("AU1");
  const KeyId id = *doc.setKey(track, 3.0f, 1.7f);
  EXPECT_FLOAT_EQ(doc.key(id)->key.time, 1.0f);
  EXPECT_FLOAT_EQ(doc.key(id)->key.value, 1.0f);
}

TEST(TimelineDocument, MovingAKeyPastItsNeighbourResortsAndKeepsTheSelection) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU4");
  ASSERT_TRUE(doc.setKey(track, 0.0f, 0.0f));
  const KeyId moved = *doc.setKey(track, 0.5f, 0.5f);
  ASSERT_TRUE(doc.setKey(track, 1.0f, 1.0f));
  doc.select(moved);
  doc.beginMove();
  EXPECT_TRUE(doc.moveSelected(0.3f, 0.1f));
  EXPECT_TRUE(doc.moveSelected(0.8f, 0.2f));  // relative to the drag start, not cumulative
  doc.endMove();
  EXPECT_TRUE(sorted(doc));
  EXPECT_EQ(times(doc, track), (std::vector<float>{0.0f, 1.0f, 1.3f}));
  EXPECT_TRUE(doc.isSelected(moved));
  EXPECT_FLOAT_EQ(doc.key(moved)->key.value, 0.7f);
  EXPECT_EQ(doc.locate(moved)->index, 2u);
  // The whole drag is one undo step.
  EXPECT_EQ(doc.undoLabel(), "move keys");
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(times(doc, track), (std::vector<float>{0.0f, 0.5f, 1.0f}));
}

TEST(TimelineDocument, MovesAreRigidAndStayInsideTheClip) {
  TimelineDocument doc("t", 2.0f);
  const size_t a = *doc.addTrack("AU1"), b = *doc.addTrack("AU2_L");
  const KeyId k1 = *doc.setKey(a, 0.4f, 0.5f);
  const KeyId k2 = *doc.setKey(b, 1.0f, 0.5f);
  doc.select(k1);
  doc.select(k2, true);
  ASSERT_TRUE(doc.moveSelectedBy(-5.0f, 0.0f));
  EXPECT_FLOAT_EQ(doc.key(k1)->key.time, 0.0f);
  EXPECT_FLOAT_EQ(doc.key(k2)->key.time, 0.6f);  // spacing kept
  ASSERT_TRUE(doc.moveSelectedBy(5.0f, 0.0f));
  EXPECT_FLOAT_EQ(doc.key(k1)->key.time, 1.4f);
  EXPECT_FLOAT_EQ(doc.key(k2)->key.time, 2.0f);
}

TEST(TimelineDocument, AKeyDroppedOnAnotherReplacesItAndUndoBringsItBack) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU4");
  const KeyId still = *doc.setKey(track, 1.0f, 0.2f);
  const KeyId moved = *doc.setKey(track, 0.5f, 0.9f);
  doc.select(moved);
  ASSERT_TRUE(doc.moveSelectedBy(0.5f, 0.0f));
  ASSERT_EQ(doc.tracks()[track].keys.size(), 1u);
  EXPECT_EQ(doc.tracks()[track].keys[0].id, moved);
  EXPECT_FALSE(doc.key(still));
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.key(still));
  EXPECT_EQ(doc.tracks()[track].keys.size(), 2u);
}

TEST(TimelineDocument, DragPassingOverAKeyDoesNotEatIt) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU4");
  const KeyId still = *doc.setKey(track, 1.0f, 0.2f);
  const KeyId moved = *doc.setKey(track, 0.5f, 0.9f);
  doc.select(moved);
  doc.beginMove();
  doc.moveSelected(0.5f, 0.0f);  // on top of `still` mid-drag
  doc.moveSelected(0.8f, 0.0f);  // and past it
  doc.endMove();
  EXPECT_TRUE(doc.key(still));
  EXPECT_EQ(times(doc, track), (std::vector<float>{1.0f, 1.3f}));
}

TEST(TimelineDocument, DeleteUndoRedoRoundTrip) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU12");
  ASSERT_TRUE(doc.setKey(track, 0.0f, 0.0f));
  const KeyId middle = *doc.setKey(track, 1.0f, 1.0f);
  ASSERT_TRUE(doc.setKey(track, 2.0f, 0.0f));
  const facial::Timeline before = doc.toTimeline();
  doc.select(middle);
  ASSERT_TRUE(doc.deleteSelected());
  EXPECT_EQ(doc.tracks()[track].keys.size(), 2u);
  EXPECT_TRUE(doc.selection().empty());
  const facial::Timeline after = doc.toTimeline();
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(facial::timelineToJson(doc.toTimeline()), facial::timelineToJson(before));
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(facial::timelineToJson(doc.toTimeline()), facial::timelineToJson(after));
  // Undo everything: back to the empty document, and redo replays it all.
  while (doc.undo()) {
  }
  EXPECT_TRUE(doc.tracks().empty());
  EXPECT_FALSE(doc.dirty());
  while (doc.redo()) {
  }
  EXPECT_EQ(facial::timelineToJson(doc.toTimeline()), facial::timelineToJson(after));
}

TEST(TimelineDocument, ANewEditClearsRedo) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU12");
  ASSERT_TRUE(doc.setKey(track, 0.5f, 0.5f));
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.canRedo());
  ASSERT_TRUE(doc.setKey(track, 1.0f, 0.5f));
  EXPECT_FALSE(doc.canRedo());
}

TEST(TimelineDocument, InterpolationPerKeyAndAutoCubicTangents) {
  TimelineDocument doc("t", 2.0f);
  const size_t track = *doc.addTrack("AU26_JawDrop");
  ASSERT_TRUE(doc.setKey(track, 0.0f, 0.0f));
  const KeyId mid = *doc.setKey(track, 1.0f, 0.5f);
  ASSERT_TRUE(doc.setKey(track, 2.0f, 1.0f));
  doc.select(mid);
  ASSERT_TRUE(doc.setSelectedInterpolation(KeyInterpolation::Step));
  EXPECT_FLOAT_EQ(doc.sample(track, 1.9f), 0.5f);
  ASSERT_TRUE(doc.setSelectedInterpolation(KeyInterpolation::Cosine));
  EXPECT_NEAR(doc.sample(track, 1.5f), 0.75f, 1e-5f);  // cosine midpoint = linear midpoint
  EXPECT_LT(doc.sample(track, 1.25f), 0.625f);         // eases out of the key
  ASSERT_TRUE(doc.setSelectedInterpolation(KeyInterpolation::Hermite));
  // Catmull-Rom slope through (0, 0) and (2, 1) is 0.5/s; the end key is flat.
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 0.5f);
  EXPECT_FLOAT_EQ(doc.tracks()[track].keys[2].key.inTangent, 0.0f);
  // Auto tangents follow edits of the neighbours.
  doc.select(doc.tracks()[track].keys[0].id);
  ASSERT_TRUE(doc.moveSelectedBy(0.0f, 0.25f));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 0.375f);
  // Level with a neighbour, the key turns flat: the curve does not overshoot it.
  ASSERT_TRUE(doc.moveSelectedBy(0.0f, 0.25f));
  EXPECT_FLOAT_EQ(doc.key(mid)->key.outTangent, 0.0f);
  ASSERT_TRUE(doc.toTimeline().validate());
}

TEST(TimelineDocument, InvalidEditsAreRejectedAndChangeNothing) {
  TimelineDocument doc("t", 2.0f);
  EXPECT_FALSE(doc.addTrack(""));
  const size_t track = *doc.addTrack("AU1");
  EXPECT_FALSE(doc.addTrack("AU1"));
  EXPECT_FALSE(doc.setKey(track, NAN, 0.5f));
  EXPECT_FALSE(doc.setKey(track, 0.5f, INFINITY));
  EXPECT_FALSE(doc.setKey(7, 0.5f, 0.5f));
  EXPECT_FALSE(doc.removeTrack(7));
  EXPECT_FALSE(doc.deleteSelected());  // nothing selected
  EXPECT_FALSE(doc.setDuration(0.0f));
  EXPECT_FALSE(doc.setDuration(NAN));
  ASSERT_TRUE(doc.setKey(track, 1.5f, 0.5f));
  const auto shorter = doc.setDuration(1.0f);
  ASSERT_FALSE(shorter);
  EXPECT_NE(shorter.error().message.find("1.5"), std::string::npos) << shorter.error().message;
  EXPECT_FLOAT_EQ(doc.duration(), 2.0f);
  doc.beginMove();
  EXPECT_FALSE(doc.moveSelected(NAN, 0.0f));
  doc.cancelMove();
  EXPECT_EQ(doc.undoLabel(), "set key");
}

TEST(TimelineDocument, SaveLoadRoundTrip) {
  const fs::path dir = testing_support::freshTempDir("editor_timeline_roundtrip");
  TimelineDocument doc("blink twice", 1.5f);
  const size_t a = *doc.addTrack("AU45_Blink");
  const size_t b = *doc.addTrack("jawOpen");
  ASSERT_TRUE(doc.setKey(a, 0.0f, 0.0f));
  ASSERT_TRUE(doc.setKey(a, 0.1f, 1.0f, KeyInterpolation::Cosine));
  ASSERT_TRUE(doc.setKey(a, 0.2f, 0.0f, KeyInterpolation::Step));
  ASSERT_TRUE(doc.setKey(b, 0.5f, 0.3f, KeyInterpolation::Hermite));
  ASSERT_TRUE(doc.setKey(b, 1.5f, 0.6f));
  ASSERT_TRUE(doc.setLoop(facial::LoopMode::PingPong));
  EXPECT_TRUE(doc.dirty());
  const fs::path file = dir / "blink.json";
  ASSERT_TRUE(doc.save(file));
  EXPECT_FALSE(doc.dirty());
  EXPECT_FALSE(fs::exists(dir / "blink.saving.json"));

  auto loaded = TimelineDocument::load(file);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_FALSE(loaded->dirty());
  EXPECT_EQ(facial::timelineToJson(loaded->toTimeline()), facial::timelineToJson(doc.toTimeline()));
  EXPECT_EQ(loaded->loop(), facial::LoopMode::PingPong);
  EXPECT_EQ(loaded->name(), "blink twice");
  for (float t = 0.0f; t <= 1.5f; t += 0.05f) {
    EXPECT_FLOAT_EQ(loaded->sample(0, t), doc.sample(0, t));
    EXPECT_FLOAT_EQ(loaded->sample(1, t), doc.sample(1, t));
  }
}

TEST(TimelineDocument, TheProjectTimelineLoadsAndSamplesLikeTheRuntime) {
  const fs::path file = testing_support::sourceDir() / "data" / "timelines" / "talk.json";
  auto doc = TimelineDocument::load(file);
  ASSERT_TRUE(doc) << doc.error().message;
  auto timeline = facial::loadTimeline(file);
  ASSERT_TRUE(timeline);
  ASSERT_EQ(doc->tracks().size(), timeline->tracks.size());
  for (size_t t = 0; t < timeline->tracks.size(); ++t)
    for (float time = 0.0f; time <= timeline->duration; time += 0.037f)
      EXPECT_FLOAT_EQ(doc->sample(t, time), facial::sampleKeys(timeline->trackKeys(t), time)) << t << " " << time;
}

TEST(TimelineDocument, BrokenFilesAreReportedWithTheirName) {
  const fs::path dir = testing_support::freshTempDir("editor_timeline_broken");
  testing_support::writeFile(dir / "broken.json", "{\"version\": 1, \"tracks\": [ {\"channel\": ");
  auto broken = TimelineDocument::load(dir / "broken.json");
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().message.find("broken.json"), std::string::npos) << broken.error().message;
  testing_support::writeFile(dir / "unsorted.json",
                             R"({"version": 1, "tracks": [{"channel": "AU1", "keys": [[0.5, 0], [0.2, 1]]}]})");
  auto unsorted = TimelineDocument::load(dir / "unsorted.json");
  ASSERT_FALSE(unsorted);
  EXPECT_NE(unsorted.error().message.find("unsorted.json"), std::string::npos) << unsorted.error().message;
  EXPECT_FALSE(TimelineDocument::load(dir / "missing.json"));
}

TEST(TimelineDocument, AFailedSaveLeavesTheOldFileIntact) {
  const fs::path dir = testing_support::freshTempDir("editor_timeline_failed_save");
  const fs::path file = dir / "clip.json";
  TimelineDocument doc("clip", 1.0f);
  ASSERT_TRUE(doc.setKey(*doc.addTrack("AU1"), 0.5f, 0.5f));
  ASSERT_TRUE(doc.save(file));
  const std::string good = readText(file);
  ASSERT_TRUE(doc.addTrack("AU2_L"));  // a track with no keys cannot be saved
  const auto failed = doc.save(file);
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.error().message.find("AU2_L"), std::string::npos) << failed.error().message;
  EXPECT_EQ(readText(file), good);
  EXPECT_TRUE(doc.dirty());
  // A save into a folder that does not exist fails and writes nothing.
  EXPECT_FALSE(doc.removeTrack(5));
  ASSERT_TRUE(doc.removeTrack(1));
  EXPECT_FALSE(doc.save(dir / "no" / "such" / "folder" / "clip.json"));
  EXPECT_FALSE(doc.save(dir));  // a folder is not a file
  EXPECT_EQ(readText(file), good);
}

}  // namespace

// ---- Dope sheet editing (issue 34): box select, clipboard, frames, mute / solo, playback ----

namespace dope {

using editor::SelectMode;

// Two tracks with keys at 0, 0.5, 1, 1.5 (values 0.1 .. 0.4 and 0.5 .. 0.8).
TimelineDocument twoTracks() {
  TimelineDocument doc("dope", 2.0f);
  const size_t a = *doc.addTrack("happy"), b = *doc.addTrack("AU26_JawDrop");
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(doc.setKey(a, 0.5f * float(i), 0.1f * float(i + 1)));
    EXPECT_TRUE(doc.setKey(b, 0.5f * float(i), 0.5f + 0.1f * float(i)));
  }
  doc.clearSelection();
  return doc;
}

TEST(TimelineDocumentDopeSheet, BoxSelectReplacesShiftExtendsCtrlToggles) {
  TimelineDocument doc = twoTracks();
  doc.selectBox(0.4f, 1.1f, {}, SelectMode::Replace);
  EXPECT_EQ(doc.selection().size(), 4u);  // 0.5 and 1 on both tracks
  const std::vector<size_t> onlyA{0};
  doc.selectBox(1.4f, 1.6f, onlyA, SelectMode::Extend);
  EXPECT_EQ(doc.selection().size(), 5u);
  doc.selectBox(0.9f, 1.6f, onlyA, SelectMode::Toggle);  // 1 and 1.5 on track 0 flip off
  EXPECT_EQ(doc.selection().size(), 3u);
  doc.selectBox(1.1f, 0.4f, onlyA, SelectMode::Replace);  // reversed bounds work
  EXPECT_EQ(doc.selection().size(), 2u);
  // Curve view boxes have a value range too.
  EXPECT_EQ(doc.keysInBox(0.0f, 2.0f, {}, 0.45f, 0.75f).size(), 3u);
  doc.selectAtTime(1.01f, SelectMode::Replace);  // within half a frame: the column at 1 s
  EXPECT_EQ(doc.selection().size(), 2u);
  doc.selectAll();
  EXPECT_EQ(doc.selection().size(), 8u);
}

TEST(TimelineDocumentDopeSheet, CopyPasteAtATimeAndDuplicateAreUndoable) {
  TimelineDocument doc = twoTracks();
  doc.selectBox(1.0f, 1.5f, {}, SelectMode::Replace);
  const editor::KeyClipboard clip = doc.copySelection();
  ASSERT_EQ(clip.keys.size(), 4u);
  EXPECT_FLOAT_EQ(clip.span, 0.5f);
  ASSERT_TRUE(doc.paste(clip, 1.8f));  // runs past the 2 s end: the clip grows to 2.3 s
  EXPECT_FLOAT_EQ(doc.duration(), 2.3f);
  EXPECT_EQ(times(doc, 0), (std::vector<float>{0.0f, 0.5f, 1.0f, 1.5f, 1.8f, 2.3f}));
  EXPECT_FLOAT_EQ(doc.tracks()[0].keys[4].key.value, 0.3f);
  EXPECT_EQ(doc.selection().size(), 4u);  // the pasted keys
  ASSERT_TRUE(doc.undo());
  EXPECT_FLOAT_EQ(doc.duration(), 2.0f);
  EXPECT_EQ(times(doc, 0).size(), 4u);
  // Paste onto a channel without a track makes it; onto existing keys replaces them.
  TimelineDocument other("other", 2.0f);
  ASSERT_TRUE(other.paste(clip, 0.0f));
  ASSERT_EQ(other.tracks().size(), 2u);
  EXPECT_EQ(other.tracks()[1].channel, "AU26_JawDrop");
  // Duplicate: one frame (30 fps) after the selection's last key.
  doc.selectBox(0.0f, 0.5f, std::vector<size_t>{1}, SelectMode::Replace);
  ASSERT_TRUE(doc.duplicateSelected());
  const auto t1 = times(doc, 1);
  ASSERT_EQ(t1.size(), 6u);  // copies at 0.5 + 1/30 and 1 + 1/30
  EXPECT_NEAR(t1[2], 0.5f + 1.0f / 30.0f, 1e-5f);
  EXPECT_NEAR(t1[4], 1.0f + 1.0f / 30.0f, 1e-5f);
  EXPECT_FALSE(TimelineDocument().paste({}, 0.0f));
  EXPECT_FALSE(doc.paste(clip, -1.0f));
}

TEST(TimelineDocumentDopeSheet, NudgeAndSnapWorkInFrames) {
  TimelineDocument doc = twoTracks();
  doc.selectBox(0.4f, 0.6f, std::vector<size_t>{0}, SelectMode::Replace);
  ASSERT_TRUE(doc.nudgeSelected(3));
  EXPECT_NEAR(times(doc, 0)[1], 0.6f, 1e-5f);  // 3 frames at 30 fps
  ASSERT_TRUE(doc.nudgeSelected(-6));
  EXPECT_NEAR(times(doc, 0)[1], 0.4f, 1e-5f);
  doc.clearSelection();
  EXPECT_FALSE(doc.nudgeSelected(1));
  // Snap at 4 fps (nothing selected: every key): 0.4 -> 0.5 collides with nothing, stays one key each.
  ASSERT_TRUE(doc.snapToFrames(4.0f));
  EXPECT_FLOAT_EQ(doc.frameRate(), 4.0f);
  EXPECT_EQ(times(doc, 0), (std::vector<float>{0.0f, 0.5f, 1.0f, 1.5f}));
  EXPECT_FLOAT_EQ(doc.snapTime(0.13f), 0.25f);
  ASSERT_TRUE(doc.undo());
  EXPECT_FLOAT_EQ(doc.frameRate(), 30.0f);
  EXPECT_FALSE(doc.snapToFrames(0.0f));
  EXPECT_FALSE(doc.snapToFrames(NAN));
}

TEST(TimelineDocumentDopeSheet, MuteAndSoloDecideWhatIsHeard) {
  TimelineDocument doc = twoTracks();
  EXPECT_TRUE(doc.audible(0) && doc.audible(1));
  ASSERT_TRUE(doc.setMuted(0, true));
  EXPECT_FALSE(doc.audible(0));
  EXPECT_TRUE(doc.audible(1));
  ASSERT_TRUE(doc.setSolo(0, true));  // solo does not un-mute
  EXPECT_FALSE(doc.audible(0));
  EXPECT_FALSE(doc.audible(1));
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.audible(0));
  EXPECT_FALSE(doc.setMuted(7, true));
  // Muting is a preview: the saved clip keeps the track.
  ASSERT_TRUE(doc.setMuted(1, true));
  EXPECT_EQ(doc.toTimeline().tracks.size(), 2u);
}

TEST(TimelineDocumentDopeSheet, LoopRangeAndSpeedShapePlayback) {
  TimelineDocument doc = twoTracks();
  ASSERT_TRUE(doc.setLoop(facial::LoopMode::Once));
  EXPECT_FLOAT_EQ(doc.playheadAt(5.0f), 2.0f);
  ASSERT_TRUE(doc.setLoopRange(0.5f, 1.5f));
  EXPECT_FLOAT_EQ(doc.playheadAt(0.25f), 0.25f);  // before the range: plays into it
  EXPECT_FLOAT_EQ(doc.playheadAt(1.25f), 1.25f);
  EXPECT_NEAR(doc.playheadAt(1.75f), 0.75f, 1e-5f);  // wraps inside it
  EXPECT_FALSE(doc.setLoopRange(1.0f, 3.0f));  // past the end
  EXPECT_FALSE(doc.setLoopRange(1.0f, 1.01f));  // shorter than a frame
  ASSERT_TRUE(doc.setSpeed(0.5f));
  EXPECT_FLOAT_EQ(doc.playback().speed, 0.5f);
  EXPECT_FALSE(doc.setSpeed(0.0f));
  ASSERT_TRUE(doc.undo());
  EXPECT_FLOAT_EQ(doc.playback().speed, 1.0f);
  ASSERT_TRUE(doc.clearLoopRange());
  EXPECT_FALSE(doc.playback().hasLoopRange);
}

TEST(TimelineDocumentDopeSheet, SettingsComeBackWithoutAnUndoStepOrUnsavedChanges) {
  TimelineDocument doc = twoTracks();
  ASSERT_TRUE(doc.snapToFrames(24.0f));
  ASSERT_TRUE(doc.setLoopRange(0.5f, 1.5f));
  ASSERT_TRUE(doc.setSpeed(0.5f));
  ASSERT_TRUE(doc.setMuted(0, true));
  ASSERT_TRUE(doc.setSolo(1, true));
  const editor::TimelineSettings saved = doc.settings();
  EXPECT_FLOAT_EQ(saved.frameRate, 24.0f);
  EXPECT_EQ(saved.muted, std::vector<std::string>{doc.tracks()[0].channel});
  EXPECT_EQ(saved.solo, std::vector<std::string>{doc.tracks()[1].channel});

  TimelineDocument reopened = twoTracks();  // the clip as its file holds it: no settings
  const bool wasDirty = reopened.dirty();
  const bool couldUndo = reopened.canUndo();
  reopened.restoreSettings(saved);
  EXPECT_EQ(reopened.settings(), saved);
  EXPECT_EQ(reopened.dirty(), wasDirty);
  EXPECT_EQ(reopened.canUndo(), couldUndo);
  // Settings that do not fit this clip are left out, not forced in.
  editor::TimelineSettings odd = saved;
  odd.playback.loopEnd = 99.0f;
  odd.frameRate = 0.0f;
  odd.muted = {"no such track"};
  reopened.restoreSettings(odd);
  EXPECT_FALSE(reopened.playback().hasLoopRange);
  EXPECT_FLOAT_EQ(reopened.frameRate(), 24.0f);
  EXPECT_TRUE(reopened.settings().muted.empty());
}

TEST(TimelineDocumentDopeSheet, GroupedEditsAreOneUndoStepOrNone) {
  TimelineDocument doc = twoTracks();
  const size_t stepsBefore = [&] { size_t n = 0; TimelineDocument copy = doc; while (copy.undo()) ++n; return n; }();
  ASSERT_TRUE(doc.grouped("two keys", [&]() -> eng::Result<void> {
    ENG_TRY(doc.setKey(0, 0.3f, 0.5f));
    ENG_TRY(doc.setKey(1, 0.6f, 0.25f));
    return {};
  }));
  EXPECT_EQ(doc.undoLabel(), "two keys");
  ASSERT_TRUE(doc.undo());
  size_t steps = 0;
  for (TimelineDocument copy = doc; copy.undo();) ++steps;
  EXPECT_EQ(steps, stepsBefore);
  ASSERT_TRUE(doc.redo());
  EXPECT_FLOAT_EQ(doc.sample(1, 0.6f), 0.25f);
  // A failing edit takes the ones before it in the group back.
  const size_t keys = doc.tracks()[0].keys.size();
  EXPECT_FALSE(doc.grouped("half", [&]() -> eng::Result<void> {
    ENG_TRY(doc.setKey(0, 0.9f, 0.5f));
    ENG_TRY(doc.setDuration(-1.0f));
    return {};
  }));
  EXPECT_EQ(doc.tracks()[0].keys.size(), keys);
  EXPECT_EQ(doc.undoLabel(), "two keys");
}

TEST(TimelineDocumentDopeSheet, KeyingOneEmotionOverTheOthersCrossfades) {
  TimelineDocument doc("emotions", 3.0f);
  constexpr std::string_view kGroup[] = {"neutral", "happy", "surprise"};
  const auto cosine = facial::KeyInterpolation::Cosine;
  ASSERT_TRUE(doc.keyExclusive("neutral", kGroup, 0.0f, cosine, facial::TangentMode::Auto));
  ASSERT_TRUE(doc.keyExclusive("happy", kGroup, 1.0f, cosine, facial::TangentMode::Auto));
  ASSERT_TRUE(doc.keyExclusive("surprise", kGroup, 2.0f, cosine, facial::TangentMode::Auto));
  ASSERT_EQ(doc.tracks().size(), 3u);
  const size_t happy = *doc.findTrack("happy"), surprise = *doc.findTrack("surprise");
  // The new tracks hold 0 at the earlier key times, so each emotion rises from its predecessor's key.
  EXPECT_EQ(times(doc, surprise), (std::vector<float>{0.0f, 1.0f, 2.0f}));
  EXPECT_FLOAT_EQ(doc.sample(happy, 0.5f), 0.5f);  // cosine midpoint
  EXPECT_LT(doc.sample(happy, 0.25f), 0.25f);      // eased
  EXPECT_FLOAT_EQ(doc.sample(happy, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(doc.sample(surprise, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(doc.sample(happy, 2.0f), 0.0f);
  EXPECT_EQ(doc.selection().size(), 3u);  // the keys at 2 s
  ASSERT_TRUE(doc.undo());
  EXPECT_FALSE(doc.findTrack("surprise").has_value());
  EXPECT_FALSE(doc.keyExclusive("giggle", kGroup, 1.0f, cosine, facial::TangentMode::Auto));
  EXPECT_FALSE(doc.keyExclusive("happy", kGroup, -1.0f, cosine, facial::TangentMode::Auto));
  ASSERT_TRUE(doc.keyExclusive("happy", kGroup, 4.0f, cosine, facial::TangentMode::Auto));  // past the end: grows
  EXPECT_FLOAT_EQ(doc.duration(), 4.0f);
}

}  // namespace dope
