#include "facial/runtime/graph/graph_json.h"

#include <gtest/gtest.h>

#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

const GraphLoadOptions kPresets{tablePresets({{"calm", {}}, {"happy", {{"AU12_LipCornerPuller_L", 1.0f}, {"AU6_CheekRaiser", 0.5f}}}})};

std::filesystem::path writeGraph(const std::string& name, const std::string& text) {
  const auto dir = testing_support::freshTempDir("graph_json_" + name);
  testing_support::writeFile(dir / "graphs" / "timelines" / "blink.json",
                             R"({"version": 1, "tracks": [{"channel": "AU45_Blink_L", "keys": [[0, 0], [0.1, 1], [0.2, 0]]}]})");
  testing_support::writeFile(dir / "graphs" / (name + ".json"), text);
  return dir / "graphs" / (name + ".json");
}

std::string loadError(const std::string& name, const std::string& text, const GraphLoadOptions& options = kPresets) {
  auto graph = loadGraph(writeGraph(name, text), options);
  EXPECT_FALSE(graph.ok()) << name << " loaded";
  return graph.ok() ? std::string() : graph.error().message;
}

// A state machine graph whose first state's first transition is `transition`.
std::string machineWith(const std::string& transition) {
  return R"({"version": 1, "channels": "actionUnits",
    "parameters": [{"name": "go", "type": "trigger"}, {"name": "level", "type": "float"}],
    "root": {"type": "stateMachine", "states": [
      {"name": "a", "node": {"type": "pose", "preset": "calm"}},
      {"name": "b", "node": {"type": "pose", "preset": "calm"}},
      {"name": "c", "node": {"type": "pose", "preset": "happy"}, "transitions": [)" +
         transition + R"(]}]}})";
}

}  // namespace

TEST(GraphJson, LoadsEveryNodeTypeWithParametersAndTimelines) {
  auto graph = loadGraph(writeGraph("every", R"({
    "version": 1, "channels": "actionUnits",
    "parameters": [{"name": "x", "type": "float", "default": 0.25}, {"name": "on", "type": "bool", "default": true},
                   {"name": "go", "type": "trigger"}, {"name": "column", "type": "float"}],
    "timelines": {"blink": "timelines/blink.json",
                  "inline": {"duration": 1, "tracks": [{"channel": "AU26_JawDrop", "keys": [[0, 0.5]]}]}},
    "root": {"type": "blink", "name": "life", "minInterval": 1, "maxInterval": 2, "input": {
      "type": "additive", "mask": {"region": "upper", "side": "left"}, "weight": 0.5,
      "layer": {"type": "timeline", "timeline": "blink", "loop": "pingpong", "speed": "x"},
      "base": {"type": "stateMachine", "name": "machine", "defaultState": "map", "states": [
        {"name": "map", "node": {"type": "controlMap", "x": "x", "y": 0.1,
           "neutral": {"type": "pose", "preset": "calm"}, "up": {"type": "pose", "preset": "happy", "intensity": 0.5},
           "down": {"type": "pose", "weights": {"AU15_LipCornerDepressor": 1}},
           "right": {"type": "timeline", "timeline": "inline"},
           "left": {"type": "pose", "preset": "calm", "overrideBlink": "block"}},
         "transitions": [{"to": "free", "duration": 0.5, "curve": {"type": "bezier", "handles": [0.4, 0, 0.2, 1]},
                          "conditions": [{"parameter": "go"}, {"parameter": "on", "value": true},
                                         {"parameter": "x", "op": ">=", "value": 0.1}]}]},
        {"name": "free", "node": {"type": "freeformMap", "x": "x", "y": "x",
           "neutral": {"type": "pose", "preset": "calm"},
           "poles": [{"at": [1, 0], "node": {"type": "pose", "preset": "happy"}},
                     {"at": [0, 1], "node": {"type": "blend", "factor": "x", "curve": "smoothstep",
                        "a": {"type": "pose", "preset": "calm"}, "b": {"type": "pose", "preset": "happy"}}}]}},
        {"name": "grid", "node": {"type": "bilinear", "expression": "column", "shape": 0.5, "duration": 0.3,
           "curve": {"type": "keyed", "keys": [[0, 0], [0.5, 0.8], [1, 1]]},
           "shapes": [[{"type": "pose", "preset": "calm"}, {"type": "pose", "preset": "happy"}],
                      [{"type": "pose", "preset": "happy"}, {"type": "pose", "preset": "calm"}]]}}],
        "anyState": [{"to": "grid", "duration": 1, "exitTime": 30, "priority": 2, "interruptible": false}]}}}})"),
                         kPresets);
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  const GraphDefinition& g = **graph;
  EXPECT_EQ(g.channelCount(), actionUnits().size());
  EXPECT_EQ(g.parameters().size(), 4u);
  EXPECT_EQ(g.timelines().size(), 2u);
  EXPECT_EQ(g.timelines()[0].name, "blink");
  const StateMachineNode* machine = g.nodeAs<StateMachineNode>(*g.findNode("machine"));
  ASSERT_NE(machine, nullptr);
  EXPECT_EQ(machine->defaultIndex, 0u);
  EXPECT_EQ(machine->states[0].transitions[0].conditions.size(), 3u);
  EXPECT_EQ(machine->states[0].transitions[0].curve.type(), EasingType::CubicBezier);
  EXPECT_FALSE(machine->anyState[0].interruptible);
  EXPECT_EQ(machine->anyState[0].exitTime, 30.0f);

  GraphInstance face = instantiate(*graph);
  face.update(0.1f);
  // map at (0.25, 0.1): up (happy at 0.5) weighs 0.1 -> AU12_L = 0.05.
  EXPECT_NEAR(face.weights()[*actionUnitIndex("AU12_LipCornerPuller_L")], 0.05f, 1e-6f);
  EXPECT_NEAR(face.weights()[*actionUnitIndex("AU26_JawDrop")], 0.25f * 0.5f, 1e-6f);  // right pole: inline timeline
}

TEST(GraphJson, PoseWeightsMayBeAnArrayOverRawTargetNames) {
  auto graph = loadGraph(writeGraph("raw", R"({"version": 1, "channels": ["jawOpen", "eyeBlink_L", "eyeBlink_R"],
      "root": {"type": "blink", "channels": ["eyeBlink_L", "eyeBlink_R"], "input": {"type": "pose", "weights": [0.4, 0, 0]}}})"));
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  GraphInstance face = instantiate(*graph);
  face.update(0.1f);
  EXPECT_FLOAT_EQ(face.weights()[0], 0.4f);
}

TEST(GraphJsonValidity, ErrorsNameTheFileTheJsonPointerAndTheProblem) {
  std::string e = loadError("duration", machineWith(R"({"to": "a", "duration": -1, "conditions": [{"parameter": "go"}]})"));
  EXPECT_NE(e.find("duration.json: /root/states/2/transitions/0/duration: must be a finite number > 0"), std::string::npos) << e;

  e = loadError("unknownParameter", machineWith(R"({"to": "a", "conditions": [{"parameter": "nope"}]})"));
  EXPECT_NE(e.find("/root/states/2/transitions/0/conditions/0/parameter: no parameter named 'nope'"), std::string::npos) << e;

  e = loadError("missingOp", machineWith(R"({"to": "a", "conditions": [{"parameter": "level", "value": 1}]})"));
  EXPECT_NE(e.find("/root/states/2/transitions/0/conditions/0: missing \"op\""), std::string::npos) << e;

  e = loadError("badOp", machineWith(R"({"to": "a", "conditions": [{"parameter": "level", "op": "~", "value": 1}]})"));
  EXPECT_NE(e.find("/conditions/0/op: unknown comparison '~'"), std::string::npos) << e;

  e = loadError("priority", machineWith(R"({"to": "a", "exitTime": 1, "priority": 0.5})"));
  EXPECT_NE(e.find("/root/states/2/transitions/0/priority: expected an integer, got 0.5"), std::string::npos) << e;

  e = loadError("unknownState", machineWith(R"({"to": "zz", "exitTime": 1})"));
  EXPECT_NE(e.find("/root/states/2/transitions/0/to: no state named 'zz'"), std::string::npos) << e;

  e = loadError("curve", machineWith(R"({"to": "a", "exitTime": 1, "curve": "bouncy"})"));
  EXPECT_NE(e.find("/root/states/2/transitions/0/curve: unknown curve 'bouncy'"), std::string::npos) << e;

  e = loadError("type", R"({"version": 1, "channels": "actionUnits", "root": {"type": "blink", "input": {"type": "dance"}}})");
  EXPECT_NE(e.find("/root/input/type: unknown node type 'dance'"), std::string::npos) << e;

  e = loadError("noLibrary", R"({"version": 1, "channels": "actionUnits", "root": {"type": "pose", "preset": "happy"}})", {});
  EXPECT_NE(e.find("/root/preset: preset 'happy' requested but no expression library was given"), std::string::npos) << e;

  e = loadError("unknownPreset", R"({"version": 1, "channels": "actionUnits", "root": {"type": "pose", "preset": "smug"}})");
  EXPECT_NE(e.find("/root/preset: unknown preset 'smug'"), std::string::npos) << e;

  e = loadError("channel", R"({"version": 1, "channels": "actionUnits", "root": {"type": "pose", "weights": {"AU99": 1}}})");
  EXPECT_NE(e.find("/root/weights/AU99: 'AU99' is not a channel of this graph"), std::string::npos) << e;

  e = loadError("weight", R"({"version": 1, "channels": ["a"], "root": {"type": "pose", "weights": [1.5]}})");
  EXPECT_NE(e.find("weight.json: /root/weights: channel 'a' weight 1.5"), std::string::npos) << e;

  e = loadError("timelineFile", R"({"version": 1, "channels": "actionUnits", "timelines": {"t": "missing.json"},
                                    "root": {"type": "timeline", "timeline": "t"}})");
  EXPECT_NE(e.find("/timelines/t: "), std::string::npos) << e;
  EXPECT_NE(e.find("missing.json"), std::string::npos) << e;

  e = loadError("timelineName", R"({"version": 1, "channels": "actionUnits", "root": {"type": "timeline", "timeline": "t"}})");
  EXPECT_NE(e.find("/root/timeline: no timeline named 't'"), std::string::npos) << e;

  e = loadError("typo", R"({"version": 1, "channels": "actionUnits", "root": {"type": "stateMachine", "stats": []}})");
  EXPECT_NE(e.find("/root/stats: unknown key"), std::string::npos) << e;

  e = loadError("version", R"({"version": 7, "channels": "actionUnits", "root": {}})");
  EXPECT_NE(e.find("version.json: /version: unsupported version 7"), std::string::npos) << e;

  e = loadError("channels", R"({"version": 1, "channels": ["a", "a"], "root": {"type": "pose", "weights": [0, 0]}})");
  EXPECT_NE(e.find("/channels: channel name 'a' appears twice"), std::string::npos) << e;

  e = loadError("triggerDefault", R"({"version": 1, "channels": ["a"], "parameters": [{"name": "t", "type": "trigger", "default": 1}],
                                      "root": {"type": "pose", "weights": [0]}})");
  EXPECT_NE(e.find("/parameters/0/default: a trigger has no default"), std::string::npos) << e;

  e = loadError("broken", R"({"version": 1, "channels": )");
  EXPECT_NE(e.find("broken.json: invalid JSON"), std::string::npos) << e;

  auto missing = loadGraph("/nonexistent/graph.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/graph.json"), std::string::npos);
}

// Nodes recurse into nodes while parsing: hostile depth is refused with one line, never a stack overflow.
TEST(GraphJsonValidity, DeepNestingIsRefusedNotACrash) {
  // A blend whose "a" is a blend ... `levels` deep, ending in a pose.
  const auto nested = [](size_t levels) {
    std::string text = R"({"version": 1, "channels": ["a"], "root": )";
    for (size_t i = 0; i < levels; ++i) text += R"({"type": "blend", "b": {"type": "pose", "weights": [0]}, "a": )";
    text += R"({"type": "pose", "weights": [1]})";
    text.append(levels, '}');
    return text + "}";
  };
  // 8,000 levels: the JSON itself (document, 8,000 blends, a pose, its weights) is too deep to parse.
  std::string e = loadError("deep8000", nested(8000));
  EXPECT_NE(e.find("deep8000.json: JSON nests 8003 levels deep, more than the 256 accepted"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  // Shallow enough for the JSON parser, too deep for the graph: the node limit names where it stopped.
  e = loadError("deep100", nested(100));
  std::string at = "deep100.json: /root";
  for (size_t i = 0; i < kMaxGraphNodeDepth; ++i) at += "/a";
  EXPECT_NE(e.find(at + ": nodes nest deeper than 64 levels, the limit"), std::string::npos) << e;
  // At the limit it loads.
  auto graph = loadGraph(writeGraph("deep64", nested(kMaxGraphNodeDepth - 1)), kPresets);
  EXPECT_TRUE(graph.ok()) << graph.error().message;
}

// A node the builder refuses (after the JSON reads fine) is reported through the same
// Result as a syntax problem: one line with the file, the node's JSON pointer and the problem.
TEST(GraphJsonValidity, ABadNodeNamesFileNodeAndProblemInOneLine) {
  const auto path = writeGraph("badNode", R"({"version": 1, "channels": "actionUnits",
    "root": {"type": "stateMachine", "states": [
      {"name": "a", "node": {"type": "blink", "minInterval": 2, "maxInterval": 1,
                             "input": {"type": "pose", "preset": "calm"}}}]}})");
  auto graph = loadGraph(path, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().kind, eng::ErrorKind::Malformed);
  EXPECT_EQ(graph.error().message,
            path.string() + ": /root/states/0/node/maxInterval: is shorter than minInterval (1 < 2)");

  // A parameter of the wrong type, found by BuildContext::checkParameter, likewise.
  const auto wrongType = writeGraph("wrongType", R"({"version": 1, "channels": "actionUnits",
    "parameters": [{"name": "go", "type": "trigger"}],
    "root": {"type": "bilinear", "expression": "go", "shapes": [
      [{"type": "pose", "preset": "calm"}, {"type": "pose", "preset": "happy"}],
      [{"type": "pose", "preset": "calm"}, {"type": "pose", "preset": "happy"}]]}})");
  graph = loadGraph(wrongType, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().kind, eng::ErrorKind::Malformed);
  EXPECT_EQ(graph.error().message, wrongType.string() + ": /root/expression: parameter 'go' is a trigger, expected a float");
}

// A state whose name was read when its node fails: the name is freed (the
// graph fuzzer found it leaked, under LeakSanitizer in tools/sanitizers/run.sh;
// a name past the short-string buffer, so that it is on the heap).
TEST(GraphJsonValidity, AStateWithABadNodeLeaksNothing) {
  const auto path = writeGraph("badStateNode", R"({"version": 1, "channels": "actionUnits",
    "root": {"type": "stateMachine", "states": [
      {"name": "a state name well past the short-string buffer", "node": {"type": "pose", "preset": "nope"}}]}})");
  auto graph = loadGraph(path, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_NE(graph.error().message.find("/root/states/0/node"), std::string::npos) << graph.error().message;
}

// Kinds survive the reader's internal conversion: a missing timeline file stays NotFound, a
// newer format version is Unsupported, and the message still names both files.
TEST(GraphJsonValidity, NestedErrorsKeepTheirKind) {
  const auto path = writeGraph("missingTimeline", R"({"version": 1, "channels": "actionUnits",
    "timelines": {"t": "gone.json"}, "root": {"type": "timeline", "timeline": "t"}})");
  auto graph = loadGraph(path, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().kind, eng::ErrorKind::NotFound) << graph.error().message;
  EXPECT_EQ(graph.error().message.rfind(path.string() + ": /timelines/t: ", 0), 0u) << graph.error().message;
  EXPECT_NE(graph.error().message.find("gone.json"), std::string::npos) << graph.error().message;

  graph = loadGraph(writeGraph("newer", R"({"version": 2, "channels": "actionUnits", "root": {}})"), kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().kind, eng::ErrorKind::Unsupported) << graph.error().message;
}

// A graph's timeline files stay in its folder, as glTF URIs do: a downloaded graph
// cannot make the program read from anywhere on the disk.
TEST(GraphJsonFiles, TimelineFilesOutsideTheGraphsFolderAreRefused) {
  const auto outside = testing_support::freshTempDir("graph_json_outside") / "t.json";
  testing_support::writeFile(outside, R"({"version": 1, "tracks": [{"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})");
  auto graphNaming = [](const std::string& file) {
    return R"({"version": 1, "channels": "actionUnits", "timelines": {"t": ")" + file +
           R"("}, "root": {"type": "timeline", "timeline": "t"}})";
  };
  std::string e = loadError("absolute", graphNaming(outside.string()));
  EXPECT_NE(e.find("/timelines/t: '" + outside.string() + "' is an absolute path"), std::string::npos) << e;
  e = loadError("dotdot", graphNaming("../timelines/../graphs/../timelines/blink.json"));
  EXPECT_NE(e.find("/timelines/t: '../timelines/../graphs/../timelines/blink.json' points outside"), std::string::npos) << e;

  const auto linked = writeGraph("linked", graphNaming("link.json"));
  std::filesystem::create_symlink(outside, linked.parent_path() / "link.json");
  auto graph = loadGraph(linked, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_NE(graph.error().message.find("'link.json' resolves (through a link) outside"), std::string::npos)
      << graph.error().message;

  // The embedder (or `play --allow-outside-paths`) may lift it for a graph it trusts.
  GraphLoadOptions trusted = kPresets;
  trusted.allowOutsidePaths = true;
  graph = loadGraph(linked, trusted);
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  graph = loadGraph(writeGraph("trustedAbsolute", graphNaming(outside.string())), trusted);
  EXPECT_TRUE(graph.ok()) << graph.error().message;
}

// A referenced file that fails is named with the kind of failure, never with
// its own message: that would quote its keys or text into the graph's error.
TEST(GraphJsonFiles, AFailingTimelineFileIsNotQuoted) {
  const auto path = writeGraph("quoting", R"({"version": 1, "channels": "actionUnits",
    "timelines": {"t": "secret.json", "u": "text.json"}, "root": {"type": "timeline", "timeline": "t"}})");
  testing_support::writeFile(path.parent_path() / "secret.json", R"({"version": 1, "api_key_4f2a": "hunter2", "tracks": []})");
  auto graph = loadGraph(path, kPresets);
  ASSERT_FALSE(graph.ok());
  const std::string& e = graph.error().message;
  EXPECT_EQ(e.rfind(path.string() + ": /timelines/t: timeline file 'secret.json' did not load (malformed)", 0), 0u) << e;
  EXPECT_EQ(e.find("api_key_4f2a"), std::string::npos) << e;
  EXPECT_EQ(e.find("hunter2"), std::string::npos) << e;

  testing_support::writeFile(path.parent_path() / "secret.json", "root:x:0:0:root:/root:/bin/bash\n");
  graph = loadGraph(path, kPresets);
  ASSERT_FALSE(graph.ok());
  EXPECT_EQ(graph.error().message.find("root:x"), std::string::npos) << graph.error().message;
  EXPECT_NE(graph.error().message.find("'secret.json' did not load (malformed)"), std::string::npos) << graph.error().message;
}
