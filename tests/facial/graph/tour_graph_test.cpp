// data/graphs/tour.json with the project's expression presets (data/expressions.json).
#include <gtest/gtest.h>

#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/rig/expression_library.h"
#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

struct Tour {
  Tour() {
    auto loaded = ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
    EXPECT_TRUE(loaded.ok()) << loaded.error().message;
    library.emplace(std::move(loaded).value());
    auto g = loadGraph(testing_support::sourceDir() / "data" / "graphs" / "tour.json", {presetLookup(*library)});
    EXPECT_TRUE(g.ok()) << g.error().message;
    graph = g.value();
    machine = *graph->findNode("emotions");
  }
  std::string stateName(const GraphInstance& face) const {
    return graph->nodeAs<StateMachineNode>(machine)->states[face.stateMachineStatus(machine)->current].name;
  }
  std::optional<ExpressionLibrary> library;
  SharedGraphDefinition graph;
  NodeIndex machine = 0;
};

}  // namespace

TEST(TourGraph, VisitsTheSixEmotionsAndComesBackToNeutral) {
  Tour tour;
  GraphInstance face = instantiate(tour.graph);
  std::vector<std::string> visited = {tour.stateName(face)};
  for (int frame = 0; frame < 60 * 17; ++frame) {
    face.update(1.0f / 60.0f);
    if (tour.stateName(face) != visited.back()) visited.push_back(tour.stateName(face));
  }
  EXPECT_EQ(visited, (std::vector<std::string>{"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust", "neutral"}));
}

TEST(TourGraph, EachEmotionSettlesOnItsPreset) {
  Tour tour;
  GraphInstance face = instantiate(tour.graph);
  std::vector<float> preset(actionUnits().size());
  for (int state = 0; state < 7; ++state) {
    // Settled: 2.0 s into each 2.4 s state (its 0.8 s blend is over).
    for (int frame = 0; frame < (state == 0 ? 120 : 144); ++frame) face.update(1.0f / 60.0f);
    const std::string name = tour.stateName(face);
    ASSERT_TRUE(ExpressionLibrary::evaluate(*tour.library->find(name), 1.0f, preset).ok());
    for (uint32_t c = 0; c < preset.size(); ++c) {
      if (actionUnits()[c].facsNumber == 45) continue;  // the blink layer owns these
      EXPECT_NEAR(face.weights()[c], preset[c], 1e-5f) << name << " " << actionUnits()[c].name;
    }
  }
}

TEST(TourGraph, TriggersJumpTheQueueAndTalkMovesOnlyTheLowerFace) {
  Tour tour;
  GraphInstance face = instantiate(tour.graph);
  face.update(0.1f);
  ASSERT_TRUE(face.setBool(*tour.graph->findParameter("autoplay"), false));
  ASSERT_TRUE(face.setTrigger(*tour.graph->findParameter("happy")));
  for (int frame = 0; frame < 60; ++frame) face.update(1.0f / 60.0f);
  EXPECT_EQ(tour.stateName(face), "happy");
  const std::vector<float> quiet(face.weights().begin(), face.weights().end());
  ASSERT_TRUE(face.setFloat(*tour.graph->findParameter("talk"), 1.0f));
  face.update(0.3f);
  EXPECT_NE(face.weights()[*actionUnitIndex("AU26_JawDrop")], quiet[*actionUnitIndex("AU26_JawDrop")]);
  for (uint32_t c = 0; c < quiet.size(); ++c) {
    if (actionUnits()[c].region == FaceRegion::Upper && actionUnits()[c].facsNumber != 45) {
      EXPECT_EQ(face.weights()[c], quiet[c]) << actionUnits()[c].name;
    }
  }
  for (int frame = 0; frame < 600; ++frame) face.update(1.0f / 60.0f);
  EXPECT_EQ(tour.stateName(face), "happy");  // autoplay off: it stays (happy: its jaw is not already fully open, so talk shows)
}
