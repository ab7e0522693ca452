// facial-editor --script under xvfb-run: the dope sheet and the curve view
// (issue 34) as a person would use them: key neutral -> happy -> surprise
// with cosine easing, box-select the last keys and move them, paste them
// later, bend a tangent in the curve view, mute / solo, loop range, speed,
// save; checked from the saved file (read by the runtime) and the log.
// Refusing broken ones needs no display.
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "editor/curve_model.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

// The program's refusal of a one-line script (parsed before the window opens: no display needed).
std::string parseError(const std::string& line) {
  return editor_test::scriptRefusal(testing_support::freshTempDir("editor_script_dope_sheet_broken"), "s.txt", line);
}

TEST(EditorScriptDopeSheet, BrokenActionsAreRefusedNamingTheLine) {
  EXPECT_NE(parseError("1 timeline-key-emotion giggle 1 cosine\n").find("s.txt:1: unknown emotion 'giggle'"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-key-emotion happy 1 bouncy\n").find("unknown easing 'bouncy' (auto, smooth, flat"),
            std::string::npos);
  EXPECT_NE(parseError("1 curve-tangent happy 1 wobbly\n").find("unknown tangent mode 'wobbly'"), std::string::npos);
  EXPECT_NE(parseError("1 curve-tangent happy 1 broken 0.5\n").find("give both slopes IN OUT, or neither"), std::string::npos);
  EXPECT_NE(parseError("1 curve-tangent happy 1.5 auto\n").find("key index is a whole number"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-nudge 1.5\n").find("whole frames"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-snap 0\n").find("1 to 1000 frames a second"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-loop 2 1\n").find("the end must come after the start"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-speed 100\n").find("0.05 to 20"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-box-select 1\n").find("'timeline-box-select' takes 2 argument(s), got 1"), std::string::npos);
  EXPECT_NE(parseError("1 timeline-paste\n").find("takes 1 argument(s), got 0"), std::string::npos);
}

TEST(EditorScriptDopeSheet, KeyEmotionsMoveTheLastKeysPasteThemLaterAndBendATangent) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_dope_sheet");
  testing_support::writeFile(dir / "session.txt",
                             editor_test::kKeyEmotionsMoveAndPaste +
                             "0.9 timeline-snap 24\n"
                             "1.0 timeline-nudge -2                    # the pasted keys, 2 frames earlier\n"
                             "1.1 curve-tangent happy 1 broken 0.5 -1.5\n"
                             "1.2 undo\n"
                             "1.3 redo\n"
                             "1.4 timeline-loop 0.5 1.5\n"
                             "1.5 timeline-speed 0.5\n"
                             "1.6 timeline-solo happy\n"
                             "1.7 timeline-mute neutral\n"
                             "1.8 screenshot curves.png\n"
                             "1.9 timeline-save session.json\n"
                             "2.0 quit\n");
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--script session.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  ASSERT_TRUE(editor_test::validationSilent(run));

  // The document after each action: tracks, keys, selected.
  std::vector<std::string> states;
  const std::regex re(R"(timeline: (\d+ tracks, \d+ keys, \d+ selected))");
  for (std::sregex_iterator it(run.log.begin(), run.log.end(), re), end; it != end; ++it) states.push_back((*it)[1]);
  ASSERT_GE(states.size(), 9u) << run.log;
  EXPECT_EQ(states[0], "1 tracks, 1 keys, 1 selected");  // neutral at 0
  EXPECT_EQ(states[1], "2 tracks, 4 keys, 2 selected");  // happy (with 0 at 0), neutral 0 at 1
  EXPECT_EQ(states[2], "3 tracks, 9 keys, 3 selected");
  EXPECT_EQ(states[3], "3 tracks, 9 keys, 6 selected");  // the box
  EXPECT_EQ(states[6], "3 tracks, 15 keys, 6 selected");  // pasted

  auto saved = facial::loadTimeline(dir / "session.json");
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_FLOAT_EQ(saved->duration, 3.5f);
  const facial::TimelineTrack* happy = saved->findTrack("happy");
  ASSERT_NE(happy, nullptr);
  ASSERT_NE(saved->findTrack("neutral"), nullptr) << "muting is a preview: the track is saved";
  const auto keys = std::span(saved->keys).subspan(happy->firstKey, happy->keyCount);
  ASSERT_EQ(keys.size(), 5u);
  const float frame = 1.0f / 24.0f;
  const float expectedTimes[] = {0.0f, 0.8f, 1.8f, 2.5f - 2 * frame, 3.5f - 2 * frame};
  const float expectedValues[] = {0.0f, 1.0f, 0.0f, 1.0f, 0.0f};
  for (size_t i = 0; i < keys.size(); ++i) {
    EXPECT_NEAR(keys[i].time, expectedTimes[i], 1e-4f) << i;
    EXPECT_FLOAT_EQ(keys[i].value, expectedValues[i]) << i;
  }
  // The bent tangent (redone after its undo): broken, its two slopes, a cubic segment.
  EXPECT_EQ(editor::curveKeyModeOf(keys[1]), editor::CurveKeyMode::Broken);
  EXPECT_FLOAT_EQ(keys[1].inTangent, 0.5f);
  EXPECT_FLOAT_EQ(keys[1].outTangent, -1.5f);
  EXPECT_EQ(keys[0].interpolation, facial::KeyInterpolation::Cosine);
  // Cosine easing from neutral: half way at 0.4 s, eased (below linear) at a quarter.
  EXPECT_NEAR(facial::sampleKeys(keys, 0.4f), 0.5f, 1e-5f);
  EXPECT_LT(facial::sampleKeys(keys, 0.2f), 0.25f);
  EXPECT_NE(run.log.find("undo: set tangent"), std::string::npos) << run.log;
}

// timeline-play is the Play button: the playhead runs with the clock until
// timeline-pause (a script that plays a clip, e.g. to time the window).
TEST(EditorScriptDopeSheet, PlayRunsThePlayheadUntilPause) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_play");
  testing_support::writeFile(dir / "ramp.json",
                             R"({"version": 1, "name": "ramp", "duration": 10.0, "loop": "once", "tracks": [)"
                             R"({"channel": "AU26_JawDrop", "interpolation": "linear", "keys": [{"t": 0, "v": 0}, {"t": 10, "v": 1}]}]})");
  testing_support::writeFile(dir / "play.txt",
                             "0.3 timeline-open ramp.json\n"
                             "0.4 timeline-play\n"
                             "1.4 timeline-pause\n"
                             "1.6 timeline-speed 1\n"
                             "1.7 quit\n");
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--script play.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  std::vector<float> playheads;
  const std::regex re(R"(playhead ([0-9.]+) s)");
  for (std::sregex_iterator it(run.log.begin(), run.log.end(), re), end; it != end; ++it) playheads.push_back(std::stof((*it)[1]));
  ASSERT_GE(playheads.size(), 3u) << run.log;
  const float paused = playheads[playheads.size() - 2];
  EXPECT_GT(paused, 0.5f) << "a second of play moved the playhead\n" << run.log;
  EXPECT_LT(paused, 5.0f) << run.log;
  EXPECT_FLOAT_EQ(playheads.back(), paused) << "paused: the playhead stays";
  EXPECT_NE(run.log.find("face from timeline"), std::string::npos) << "playing puts the timeline on the face\n" << run.log;
}

}  // namespace
