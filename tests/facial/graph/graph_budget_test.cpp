// Graph nodes under one budget per load (issue 37): a pose leaf is a few
// bytes of JSON and a float per channel in the definition, and stateful nodes
// add poses to every character. The builder charges each node as it is added
// and stops at the budget, so the parser stops reading too.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/graph_instance.h"

namespace {

using namespace facial;

ChannelSet manyChannels(size_t count) {
  std::vector<std::string> names;
  for (size_t c = 0; c < count; ++c) names.push_back("c" + std::to_string(c));
  auto set = ChannelSet::fromNames(names);
  EXPECT_TRUE(set) << set.error().message;
  return std::move(set).value();
}

TEST(GraphBudget, PoseLeavesAreChargedAsTheyAreAdded) {
  constexpr size_t kChannels = 2000, kBudget = size_t{8} << 20;
  GraphBuilder b(manyChannels(kChannels), kBudget);
  size_t accepted = 0;
  for (; accepted < 10'000; ++accepted)
    if (b.add(PoseNode{.weights = std::vector<float>(kChannels, 0.0f)}) == kNoNode) break;
  // Each leaf holds kChannels floats: the budget takes at most this many.
  EXPECT_LE(accepted, kBudget / (kChannels * sizeof(float)));
  EXPECT_GE(accepted, kBudget / (kChannels * sizeof(float)) / 2);
  ASSERT_TRUE(b.budgetError());
  const std::string& message = b.budgetError()->message;
  EXPECT_EQ(b.budgetError()->kind, eng::ErrorKind::TooLarge);
  EXPECT_EQ(message.rfind("node " + std::to_string(accepted) + " (pose): ", 0), 0u) << message;
  EXPECT_NE(message.find("load budget of " + std::to_string(kBudget) + " bytes"), std::string::npos) << message;
  // Nothing more is kept, and build() says the same.
  EXPECT_EQ(b.add(PoseNode{.weights = std::vector<float>(kChannels, 0.0f)}), kNoNode);
  EXPECT_EQ(b.nodeCount(), accepted);
  b.setRoot(0);
  auto built = b.build();
  ASSERT_FALSE(built);
  EXPECT_EQ(built.error().message, message);
}

TEST(GraphBudget, StatefulNodesAreChargedForTheStateOfEveryInstance) {
  GraphBuilder b(manyChannels(1000), size_t{1} << 20);
  const uint32_t stride = 1000 + kPoseLaneCount;
  // A state machine keeps two poses per character: ~8 KB each, so the budget fits ~120.
  size_t accepted = 0;
  for (; accepted < 1000; ++accepted)
    if (b.add(StateMachineNode{}) == kNoNode) break;
  EXPECT_LE(accepted, (size_t{1} << 20) / (2 * stride * sizeof(float)));
  EXPECT_TRUE(b.budgetError());
}

TEST(GraphBudget, InstanceBytesCountScratchOutputAndStates) {
  GraphBuilder b(manyChannels(100));
  const NodeIndex a = b.add(PoseNode{.weights = std::vector<float>(100, 0.0f)});
  const NodeIndex c = b.add(PoseNode{.weights = std::vector<float>(100, 1.0f)});
  b.setRoot(b.add(BlendNode{.a = a, .b = c}));
  auto graph = b.build();
  ASSERT_TRUE(graph) << graph.error().message;
  const size_t pose = (*graph)->poseStride() * sizeof(float);
  EXPECT_GE(GraphInstance::bytesFor(**graph), (size_t{(*graph)->scratchPoseCount()} + 1) * pose + 3 * sizeof(NodeState));
  EXPECT_EQ(GraphInstance::nodeStateBytes(StateMachineNode{}, (*graph)->poseStride()), sizeof(NodeState) + 2 * pose);
}

}  // namespace
