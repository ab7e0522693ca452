#include "facial/runtime/graph/nodes/pose_node.h"

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

TEST(PoseNode, ExplicitWeightsComeOutAsGiven) {
  GraphBuilder b(threeChannels());
  b.setRoot(addPose(b, {0.1f, 0.5f, 0.9f}));
  GraphInstance face = instantiate(buildGraph(b));
  ASSERT_TRUE(face.update(0.016f));
  EXPECT_EQ(std::vector<float>(face.weights().begin(), face.weights().end()), (std::vector<float>{0.1f, 0.5f, 0.9f}));
}

TEST(PoseNode, PresetAtAnIntensityMapsActionUnitsOntoChannelsByName) {
  const PresetLookup presets = tablePresets({{"happy", {{"AU6_CheekRaiser", 0.8f}, {"AU12_LipCornerPuller_L", 1.0f}}}});
  auto weights = presetPose(presets, "happy", 0.5f, ChannelSet::actionUnits());
  ASSERT_TRUE(weights.ok()) << weights.error().message;
  EXPECT_FLOAT_EQ((*weights)[*actionUnitIndex("AU6_CheekRaiser")], 0.4f);
  EXPECT_FLOAT_EQ((*weights)[*actionUnitIndex("AU12_LipCornerPuller_L")], 0.5f);
  EXPECT_FLOAT_EQ((*weights)[*actionUnitIndex("AU4_BrowLowerer")], 0.0f);

  // Over raw names only the channels named like units receive weight.
  const std::vector<std::string> names = {"jawOpen", "AU6_CheekRaiser"};
  auto raw = presetPose(presets, "happy", 1.0f, ChannelSet::fromNames(names).value());
  ASSERT_TRUE(raw.ok());
  EXPECT_EQ(*raw, (std::vector<float>{0.0f, 0.8f}));
}

TEST(PoseNode, ScaleParameterScalesWeightsAndTheBlinkOverrideLane) {
  GraphBuilder b(threeChannels());
  const ParameterIndex s = b.addFloat("s", 0.5f);
  b.setRoot(b.add(PoseNode{.weights = {0.2f, 0.4f, 0.8f}, .scale = FloatInput::bound(s), .overrideBlink = VrmOverride::Blend}));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  EXPECT_FLOAT_EQ(face.weights()[2], 0.4f);
  EXPECT_FLOAT_EQ(face.pose()[3 + kLaneOverrideBlinkBlend], 0.5f);
  EXPECT_FLOAT_EQ(face.pose()[3 + kLaneOverrideBlinkBlock], 0.0f);
  ASSERT_TRUE(face.setFloat(s, 1.0f));
  face.update(0.0f);
  EXPECT_FLOAT_EQ(face.weights()[1], 0.4f);
}

TEST(PoseNodeValidity, WeightsMustCoverTheChannelsWithinZeroOne) {
  GraphBuilder wrongSize(threeChannels());
  wrongSize.setRoot(addPose(wrongSize, {0.1f, 0.2f}));
  EXPECT_NE(buildError(wrongSize).find("node 0 (pose)/weights: has 2 entries, the graph has 3 channels"), std::string::npos);

  GraphBuilder outside(threeChannels());
  outside.setRoot(addPose(outside, {0.1f, 1.5f, 0.0f}));
  EXPECT_NE(buildError(outside).find("channel 'b' weight 1.5"), std::string::npos);

  auto unknown = presetPose(tablePresets({}), "smug", 1.0f, ChannelSet::actionUnits());
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("smug"), std::string::npos);
  EXPECT_FALSE(presetPose(PresetLookup{}, "happy", 1.0f, ChannelSet::actionUnits()).ok());
}
