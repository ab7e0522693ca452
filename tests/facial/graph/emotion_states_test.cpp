#include "facial/runtime/graph/emotion_states.h"

#include <gtest/gtest.h>

#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/rig/expression_library.h"
#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

TEST(EmotionStates, OneStatePerBasicEmotionHoldingItsPreset) {
  auto library = ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
  ASSERT_TRUE(library.ok()) << library.error().message;
  GraphBuilder b(ChannelSet::actionUnits());
  const ParameterIndex next = b.addTrigger("next");
  auto states = addEmotionStates(b, presetLookup(*library), 0.5f);
  ASSERT_TRUE(states.ok()) << states.error().message;
  ASSERT_EQ(states->size(), kEmotionCount);
  for (size_t i = 0; i < states->size(); ++i) EXPECT_EQ((*states)[i].name, emotionNames()[i]);

  StateMachineNode machine{.states = std::move(states).value(), .defaultState = "happy"};
  for (MachineState& s : machine.states) s.transitions.push_back({.to = "sad", .duration = 0.5f, .conditions = {{next}}});
  b.setRoot(b.add(std::move(machine)));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  std::vector<float> happy(actionUnits().size());
  ASSERT_TRUE(ExpressionLibrary::evaluate(*library->find("happy"), 0.5f, happy).ok());
  for (size_t c = 0; c < happy.size(); ++c) EXPECT_FLOAT_EQ(face.weights()[c], happy[c]) << actionUnits()[c].name;
  EXPECT_GT(face.weights()[*actionUnitIndex("AU12_LipCornerPuller_L")], 0.0f);
}

TEST(EmotionStatesValidity, AMissingPresetNamesItAndTheKnownOnes) {
  auto library = ExpressionLibrary::parse(R"({"version": 1, "expressions": {"neutral": {}, "happy": {}}})", "two.json");
  ASSERT_TRUE(library.ok()) << library.error().message;
  GraphBuilder b(ChannelSet::actionUnits());
  auto states = addEmotionStates(b, presetLookup(*library));
  ASSERT_FALSE(states.ok());
  EXPECT_NE(states.error().message.find("unknown expression preset 'sad' (known: neutral, happy)"), std::string::npos)
      << states.error().message;
}
