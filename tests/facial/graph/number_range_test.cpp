// Every number a graph, timeline or curve file holds is range-checked (issue
// 37): NaN, infinity and 1e30 in any field (key times, values, Hermite
// tangents, durations, thresholds, defaults, positions) end in one line
// naming the file and the field's JSON pointer. And a graph file's nodes are
// charged to the load's budget through the file loader, not only through
// GraphBuilder.
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/curve_json.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"

namespace {

using facial::Json;

void writeJson(const std::filesystem::path& path, const Json& doc) {
  testing_support::writeFile(path, doc.dump());
}

// One line, naming the file and the field, saying the range.
void expectRangeError(const std::string& message, const std::string& file, const std::string& pointer) {
  EXPECT_EQ(message.rfind(file + ": " + pointer + ": number ", 0), 0u) << message;
  EXPECT_NE(message.find("is outside [-1e+06, 1e+06]"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

Json hermiteTimeline() {
  return {{"version", 1},
          {"tracks", Json::array({{{"channel", "jawOpen"},
                                   {"interpolation", "hermite"},
                                   {"keys", Json::array({{{"t", 0}, {"v", 0}, {"out", 2}},
                                                         {{"t", 1}, {"v", 1}, {"in", -1}}})}}})}};
}

class NumberRange : public ::testing::Test {
 protected:
  std::filesystem::path dir_ = testing_support::freshTempDir("number_range");
};

TEST_F(NumberRange, TheReferenceTimelineLoads) {
  writeJson(dir_ / "t.json", hermiteTimeline());
  auto timeline = facial::loadTimeline(dir_ / "t.json");
  ASSERT_TRUE(timeline) << timeline.error().message;
  EXPECT_EQ(timeline->keys[0].outTangent, 2.0f);
}

TEST_F(NumberRange, HugeHermiteTangentsInATimelineFileAreRefused) {
  for (const char* field : {"out", "in"}) {
    Json doc = hermiteTimeline();
    doc["tracks"][0]["keys"][field == std::string("out") ? 0 : 1][field] = 1e30;
    const std::filesystem::path file = dir_ / (std::string(field) + ".json");
    writeJson(file, doc);
    auto timeline = facial::loadTimeline(file);
    ASSERT_FALSE(timeline) << field;
    expectRangeError(timeline.error().message, file.string(),
                     std::string("/tracks/0/keys/") + (field == std::string("out") ? "0/" : "1/") + field);
  }
}

// JSON text cannot hold NaN or infinity, and 1e400 overflows the JSON
// reader; an embedder's in-memory document can hold both.
TEST_F(NumberRange, InfinityAndNaNTangentsAreRefused) {
  const std::filesystem::path file = dir_ / "inf.json";
  std::string text = hermiteTimeline().dump();
  text.replace(text.find("\"out\":2"), 7, "\"out\":1e400");
  testing_support::writeFile(file, text);
  auto fromFile = facial::loadTimeline(file);  // the JSON reader refuses it, naming the number
  ASSERT_FALSE(fromFile);
  EXPECT_EQ(fromFile.error().message.rfind(file.string() + ": ", 0), 0u) << fromFile.error().message;
  EXPECT_NE(fromFile.error().message.find("1e400"), std::string::npos) << fromFile.error().message;
  Json doc = hermiteTimeline();
  doc["tracks"][0]["keys"][1]["in"] = std::numeric_limits<double>::quiet_NaN();
  auto inMemory = facial::timelineFromJson(doc, "t");
  ASSERT_FALSE(inMemory);
  EXPECT_EQ(inMemory.error().message.rfind("/tracks/0/keys/1/in: number ", 0), 0u) << inMemory.error().message;
}

TEST_F(NumberRange, KeyTimesAndDurationsPastTheRangeAreRefused) {
  Json late = hermiteTimeline();
  late["tracks"][0]["keys"][1]["t"] = 1e30;
  auto key = facial::timelineFromJson(late, "t");
  ASSERT_FALSE(key);
  EXPECT_EQ(key.error().message.rfind("/tracks/0/keys/1/t: number 1e+30 is outside", 0), 0u) << key.error().message;
  Json longClip = hermiteTimeline();
  longClip["duration"] = -1e30;
  auto duration = facial::timelineFromJson(longClip, "t");
  ASSERT_FALSE(duration);
  EXPECT_EQ(duration.error().message.rfind("/duration: number -1e+30 is outside", 0), 0u) << duration.error().message;
}

TEST_F(NumberRange, CurvesAndKeysReadAloneAreChecked) {
  auto keys = facial::keyframesFromJson(Json::array({Json::array({0, 0}), Json::array({1e30, 1})}), facial::KeyInterpolation::Linear);
  ASSERT_FALSE(keys);
  EXPECT_EQ(keys.error().message.rfind("/1/0: number 1e+30", 0), 0u) << keys.error().message;
  auto curve = facial::easingCurveFromJson({{"type", "bezier"}, {"handles", {0.2, 1e30, 0.8, 1}}});
  ASSERT_FALSE(curve);
  EXPECT_EQ(curve.error().message.rfind("/handles/1: number 1e+30", 0), 0u) << curve.error().message;
}

// A graph whose every kind of float is in range, then each made huge in turn.
Json graphWithEveryFloat() {
  Json machine = {{"type", "stateMachine"},
                  {"defaultState", "a"},
                  {"states", Json::array({{{"name", "a"},
                                           {"node", {{"type", "pose"}, {"weights", {{"AU1_InnerBrowRaiser", 0.5}}}}},
                                           {"transitions", Json::array({{{"to", "b"},
                                                                         {"duration", 0.5},
                                                                         {"exitTime", 2},
                                                                         {"conditions", Json::array({{{"parameter", "x"},
                                                                                                      {"op", ">"},
                                                                                                      {"value", 0.5}}})}}})}},
                                          {{"name", "b"}, {"node", {{"type", "timeline"}, {"timeline", "talk"}, {"speed", 1.5}}}}})}};
  Json talk = hermiteTimeline();
  talk.erase("version");
  talk["tracks"][0]["channel"] = "AU26_JawDrop";
  return {{"version", 1},
          {"channels", "actionUnits"},
          {"parameters", Json::array({{{"name", "x"}, {"type", "float"}, {"default", 0.25}}})},
          {"timelines", {{"talk", talk}}},
          {"root", {{"type", "blend"}, {"factor", 0.5}, {"a", machine}, {"b", {{"type", "pose"}, {"weights", Json::object()}}}}}};
}

TEST_F(NumberRange, EveryFloatOfAGraphFileIsChecked) {
  writeJson(dir_ / "ok.json", graphWithEveryFloat());
  auto ok = facial::loadGraph(dir_ / "ok.json");
  ASSERT_TRUE(ok) << ok.error().message;
  const std::string fields[] = {"/parameters/0/default",
                                "/timelines/talk/tracks/0/keys/0/out",
                                "/timelines/talk/tracks/0/keys/1/t",
                                "/root/factor",
                                "/root/a/states/0/node/weights/AU1_InnerBrowRaiser",
                                "/root/a/states/0/transitions/0/duration",
                                "/root/a/states/0/transitions/0/exitTime",
                                "/root/a/states/0/transitions/0/conditions/0/value",
                                "/root/a/states/1/node/speed"};
  for (const std::string& field : fields) {
    Json doc = graphWithEveryFloat();
    doc[Json::json_pointer(field)] = 1e30;
    const std::filesystem::path file = dir_ / "huge.json";
    writeJson(file, doc);
    auto graph = facial::loadGraph(file);
    ASSERT_FALSE(graph) << field;
    expectRangeError(graph.error().message, file.string(), field);
  }
}

TEST_F(NumberRange, ProgrammaticKeysOutsideTheRangeAreRefused) {
  facial::Keyframe a{.time = 0, .value = 0, .outTangent = 1e30f, .interpolation = facial::KeyInterpolation::Hermite};
  facial::Keyframe b{.time = 1, .value = 1};
  const facial::Keyframe keys[] = {a, b};
  auto valid = facial::validateKeys(keys);
  ASSERT_FALSE(valid);
  EXPECT_EQ(valid.error().message, "key 0 out-tangent 1e+30 is not a finite number within [-1e+06, 1e+06]");
  a.outTangent = std::numeric_limits<float>::infinity();
  const facial::Keyframe infinite[] = {a, b};
  EXPECT_FALSE(facial::validateKeys(infinite));
}

// A graph file of many pose states over many channels: each pose is a float
// per channel, charged as it is read, so the file loader stops at the budget
// with one line naming the file, the node and the limit.
Json graphOfPoses(size_t channels, size_t states) {
  Json names = Json::array();
  for (size_t c = 0; c < channels; ++c) names.push_back("c" + std::to_string(c));
  Json list = Json::array();
  for (size_t s = 0; s < states; ++s)
    list.push_back({{"name", "s" + std::to_string(s)}, {"node", {{"type", "pose"}, {"weights", {{"c0", 0.5}}}}}});
  return {{"version", 1},
          {"channels", names},
          {"root", {{"type", "stateMachine"}, {"defaultState", "s0"}, {"states", list}}}};
}

TEST_F(NumberRange, AGraphFilePastItsBudgetFailsNamingFileAndBudget) {
  constexpr size_t kBudget = size_t{4} << 20;
  const std::filesystem::path file = dir_ / "huge_graph.json";
  // 2000 channels: 8 KB a pose, so ~500 poses fill 4 MiB; the file holds 2000.
  writeJson(file, graphOfPoses(2000, 2000));
  facial::GraphLoadOptions options;
  options.maxBytes = kBudget;
  auto graph = facial::loadGraph(file, options);
  ASSERT_FALSE(graph);
  const std::string& message = graph.error().message;
  EXPECT_EQ(graph.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(": /root/states/"), std::string::npos) << message;
  EXPECT_NE(message.find("(2000 channels) would take"), std::string::npos) << message;
  EXPECT_NE(message.find("load budget of " + std::to_string(kBudget) + " bytes"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  // The same file within the default budget loads.
  auto fits = facial::loadGraph(file);
  ASSERT_TRUE(fits) << fits.error().message;
}

}  // namespace
