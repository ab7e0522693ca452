// Parsing timelines, graphs (parameters, timelines, states, named nodes) and
// channel sets does work linear in the names they hold (issue 37): every
// name is looked up through a hash, not searched for among the ones before.
// Work is counted (tests/common/work_scaling.h), not timed.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/graph/channel_set.h"
#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/work_scaling.h"

namespace {

using facial::Json;
using testing_support::expectLinearWork;

std::string name(const char* prefix, size_t i) { return prefix + std::to_string(i); }

Json timelineWithTracks(size_t tracks) {
  Json t = {{"version", 1}, {"tracks", Json::array()}};
  for (size_t i = 0; i < tracks; ++i)
    t["tracks"].push_back({{"channel", name("c", i)}, {"keys", Json::array({Json::array({0, 0}), Json::array({1, 1})})}});
  return t;
}

TEST(ParserScaling, TimelineTracksAreLinear) {
  expectLinearWork([](size_t n) {
    auto timeline = facial::timelineFromJson(timelineWithTracks(n), "t");
    ASSERT_TRUE(timeline) << timeline.error().message;
    ASSERT_EQ(timeline->tracks.size(), n);
  }, 500);
}

TEST(ParserScaling, ADuplicateTrackIsStillFound) {
  Json t = timelineWithTracks(50);
  t["tracks"].push_back(t["tracks"][17]);
  auto timeline = facial::timelineFromJson(t, "t");
  ASSERT_FALSE(timeline);
  EXPECT_NE(timeline.error().message.find("'c17' already has a track"), std::string::npos) << timeline.error().message;
}

TEST(ParserScaling, ChannelSetNamesAreLinear) {
  expectLinearWork([](size_t n) {
    std::vector<std::string> names;
    for (size_t i = 0; i < n; ++i) names.push_back(name("target", i));
    auto set = facial::ChannelSet::fromNames(names);
    ASSERT_TRUE(set) << set.error().message;
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(set->find(names[i]), i);
  }, 1000);
}

// n float parameters, n inline timelines, and a state machine of n states,
// state i a timeline node playing timeline i, scaled by parameter i, with a
// transition to state i + 1 on it.
Json graphOfSize(size_t n) {
  Json g = {{"version", 1}, {"channels", "actionUnits"}, {"parameters", Json::array()}, {"timelines", Json::object()}};
  Json states = Json::array();
  for (size_t i = 0; i < n; ++i) {
    g["parameters"].push_back({{"name", name("p", i)}, {"type", "float"}});
    g["timelines"][name("t", i)] = {{"tracks", Json::array({{{"channel", "AU1_InnerBrowRaiser"}, {"keys", Json::array({Json::array({0, 0}), Json::array({1, 1})})}}})}};
    Json state = {{"name", name("s", i)}, {"node", {{"type", "timeline"}, {"name", name("n", i)}, {"timeline", name("t", i)}}}};
    state["transitions"] = Json::array({{{"to", name("s", (i + 1) % n)}, {"duration", 0.5},
                                         {"conditions", Json::array({{{"parameter", name("p", i)}, {"op", ">"}, {"value", 0.5}}})}}});
    states.push_back(state);
  }
  g["root"] = {{"type", "stateMachine"}, {"name", "machine"}, {"defaultState", name("s", n / 2)}, {"states", states}};
  return g;
}

TEST(ParserScaling, GraphParametersTimelinesAndStatesAreLinear) {
  expectLinearWork([](size_t n) {
    auto graph = facial::parseGraph(graphOfSize(n), "graph.json");
    ASSERT_TRUE(graph) << graph.error().message;
    ASSERT_EQ((*graph)->parameters().size(), n);
    ASSERT_EQ((*graph)->findNode(name("n", n - 1)).has_value(), true);
  }, 200);
}

}  // namespace
