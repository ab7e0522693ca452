// facial-editor --script under xvfb-run: the state machine diagram's edits
// (add, rename, remove states; add and edit a transition; save) and Record
// over the control map and the bilinear pad, checked from the outside: the
// saved graph read back by the runtime's loader, the recorded keys in the
// saved timeline, the log and the screenshot.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "editor/graph_document.h"
#include "editor/timeline_document.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/rig/expression_library.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

size_t keyCount(const editor::TimelineDocument& doc) {
  size_t keys = 0;
  for (const auto& track : doc.tracks()) keys += track.keys.size();
  return keys;
}

}  // namespace

TEST(EditorGraphScript, DiagramEditsSaveTheGraphTheRuntimeReads) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_graph");
  testing_support::writeFile(dir / "graph.txt",
                             "0.2 graph-add-state smirk happily_disgusted_missing\n"  // refused by the runtime: undone
                             "0.3 graph-add-state smirk happy\n"
                             "0.4 graph-add-transition neutral smirk smirk 0.5 cosine\n"
                             "0.5 graph-edit-transition neutral smirk 0.7 smoothstep 1.5 no\n"
                             "0.6 graph-rename-state smirk grin\n"
                             "0.7 graph-add-state doomed sad\n"
                             "0.8 graph-remove-state doomed\n"
                             "0.9 graph-save edited.json\n"
                             "1.0 trigger happy\n"
                             "1.2 screenshot diagram.png\n"
                             "1.4 quit\n");
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--script graph.txt", 20.0f);
  EXPECT_EQ(run.exitCode, 1) << "the first add names no preset:\n" << run.log;
  ASSERT_TRUE(editor_test::validationSilent(run));
  EXPECT_NE(run.log.find("graph.txt:1: graph-add-state smirk happily_disgusted_missing: failed"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("1 scripted action(s) failed"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("graph: 8 states, 15 transitions, modified"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("graph saved: edited.json"), std::string::npos) << run.log;

  auto presets = facial::ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
  ASSERT_TRUE(presets.ok());
  auto graph = facial::loadGraph(dir / "edited.json", {.presets = facial::presetLookup(*presets)});
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  const auto* machine = (*graph)->nodeAs<facial::StateMachineNode>(*(*graph)->findNode("emotions"));
  ASSERT_NE(machine, nullptr);
  ASSERT_TRUE(machine->findState("grin"));
  EXPECT_FALSE(machine->findState("smirk"));
  EXPECT_FALSE(machine->findState("doomed"));
  const facial::Transition& t = machine->states[0].transitions.back();
  EXPECT_EQ(t.to, "grin");
  EXPECT_FLOAT_EQ(t.duration, 0.7f);
  EXPECT_EQ(t.curve.type(), facial::EasingType::Smoothstep);
  ASSERT_TRUE(t.exitTime);
  EXPECT_FLOAT_EQ(*t.exitTime, 1.5f);
  EXPECT_FALSE(t.interruptible);
  EXPECT_TRUE((*graph)->findParameter("smirk")) << "the new trigger is declared";
}

TEST(EditorGraphScript, RecordWritesAFewKeysPerSecondIntoTheTimeline) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_record");
  testing_support::writeFile(dir / "record.txt",
                             "0.2 pad 0 0\n"
                             "0.3 record-start\n"
                             "0.5 pad 0.5 0\n"
                             "0.7 pad 1 0\n"
                             "0.9 pad 0.5 0.5\n"
                             "1.1 pad 0 0\n"
                             "1.3 record-stop\n"
                             "1.4 timeline-save control_map.json\n"
                             "1.5 bilinear-pad 0 0\n"
                             "1.6 record-start\n"
                             "1.8 bilinear-pad 0 0.5\n"
                             "2.0 bilinear-pad 0 1\n"
                             "2.2 bilinear-pad 1 1\n"
                             "2.3 screenshot bilinear.png\n"
                             "2.4 record-stop\n"
                             "2.5 timeline-save both.json\n"
                             "2.6 quit\n");
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--script record.txt", 30.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  EXPECT_NE(run.log.find("record: started at 0.000 s"), std::string::npos) << run.log;

  auto first = editor::TimelineDocument::load(dir / "control_map.json");
  ASSERT_TRUE(first.ok()) << first.error().message;
  auto both = editor::TimelineDocument::load(dir / "both.json");
  ASSERT_TRUE(both.ok()) << both.error().message;
  // The happy pole raises the smile: its track was recorded, and it peaks.
  const auto smile = first->findTrack("AU12_LipCornerPuller_L");
  ASSERT_TRUE(smile) << run.log;
  float peak = 0.0f;
  for (const auto& k : first->tracks()[*smile].keys) peak = std::max(peak, k.key.value);
  EXPECT_GT(peak, 0.5f);
  // A few keys a second per track (the frames come every ~0.1 s under xvfb: few to drop here;
  // key_recorder_test shows 121 frames becoming 12 keys).
  const float seconds = first->tracks()[*smile].keys.back().key.time - first->tracks()[*smile].keys.front().key.time;
  for (const auto& track : first->tracks())
    EXPECT_LE(float(track.keys.size()), 6.0f * seconds + 2.0f) << track.channel << " over " << seconds << " s";
  std::printf("recorded: %zu tracks, %zu keys over %.2f s (control map); %zu tracks, %zu keys (both takes)\n",
              first->tracks().size(), keyCount(*first), seconds, both->tracks().size(), keyCount(*both));
  // The bilinear take went on from the playhead (0 s) over the control map's keys. Its
  // surprise corner (s = 1, t = 1) is the emotion only the pad sets (the maps' graphs
  // blend action units), and it opened the jaw.
  EXPECT_FALSE(first->findTrack("surprise"));
  const auto surprise = both->findTrack("surprise");
  const auto jaw = both->findTrack("AU26_JawDrop");
  ASSERT_TRUE(surprise && jaw) << run.log;
  const editor::DocumentKey& end = both->tracks()[*surprise].keys.back();
  EXPECT_GT(end.key.value, 0.9f);
  EXPECT_GT(both->sample(*jaw, end.key.time), 0.5f);
}

TEST(EditorGraphScript, BadArgumentsAreRefusedBeforeTheWindowOpens) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_graph_refused");
  const std::pair<const char*, const char*> cases[] = {
      {"0.1 graph-add-transition neutral happy happy 0.5 wobbly\n", "bad.txt:1: unknown easing 'wobbly' (linear, cosine, smoothstep)"},
      {"0.1 graph-edit-transition neutral happy 0.5 cosine soon no\n",
       "bad.txt:1: exit time 'soon' is not a number of seconds >= 0 (or '-': none)"},
      {"0.1 graph-edit-transition neutral happy 0.5 cosine - maybe\n", "bad.txt:1: interruption rule 'maybe' is not yes or no"},
      {"0.1 bilinear-pad 0.5 1.5\n", "bad.txt:1: bilinear-pad s, t must lie in [0, 1]"},
  };
  for (const auto& [line, message] : cases) {
    testing_support::writeFile(dir / "bad.txt", line);
    const editor_test::EditorRun run = editor_test::runEditor(dir, "--script bad.txt", 5.0f);
    EXPECT_EQ(run.exitCode, 1) << run.log;
    EXPECT_NE(run.log.find(message), std::string::npos) << run.log;
    EXPECT_EQ(run.log.find("validation on"), std::string::npos) << "no window opened:\n" << run.log;
  }
}
