#include "facial/runtime/graph/graph_builder.h"

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

TEST(GraphBuilder, BuildsAShareableDefinitionWithNamedNodesAndParameters) {
  GraphBuilder b(threeChannels());
  const ParameterIndex t = b.addFloat("t", 0.25f);
  b.addBool("on", true);
  b.addTrigger("go");
  const NodeIndex p0 = b.add(PoseNode{.weights = {0, 0, 0}}, "calm");
  const NodeIndex p1 = addPose(b, {1, 1, 1});
  b.setRoot(b.add(BlendNode{.a = p0, .b = p1, .factor = FloatInput::bound(t)}, "mix"));
  const SharedGraphDefinition graph = buildGraph(b);
  ASSERT_TRUE(graph);
  EXPECT_EQ(graph->findParameter("on"), 1u);
  EXPECT_EQ(graph->parameters()[1].defaultValue, 1.0f);
  EXPECT_EQ(graph->findNode("calm"), p0);
  EXPECT_EQ(graph->root(), *graph->findNode("mix"));
  EXPECT_EQ(graph->poseStride(), 3u + kPoseLaneCount);
  EXPECT_EQ(graph->inputs(graph->root()).size(), 2u);
  EXPECT_EQ(graph->scratchPoseCount(), 1u);
  EXPECT_NE(graph->nodeAs<BlendNode>(graph->root()), nullptr);
  EXPECT_EQ(graph->nodeAs<PoseNode>(graph->root()), nullptr);
}

TEST(GraphBuilder, ScratchPoseCountFollowsTheDeepestChain) {
  // blend(blend(p, blend(p, p)), p): the inner blends hold one scratch pose each while their children run.
  GraphBuilder b(threeChannels());
  const NodeIndex inner = b.add(BlendNode{.a = addPose(b, {0, 0, 0}), .b = addPose(b, {1, 0, 0})});
  const NodeIndex middle = b.add(BlendNode{.a = addPose(b, {0, 1, 0}), .b = inner});
  b.setRoot(b.add(BlendNode{.a = middle, .b = addPose(b, {0, 0, 1})}));
  EXPECT_EQ(buildGraph(b)->scratchPoseCount(), 3u);
}

TEST(GraphBuilderValidity, WiringMustFormATreeUnderTheRoot) {
  GraphBuilder noRoot(threeChannels());
  addPose(noRoot, {0, 0, 0});
  EXPECT_NE(buildError(noRoot).find("root node"), std::string::npos);

  GraphBuilder unset(threeChannels());
  unset.setRoot(unset.add(BlendNode{.a = addPose(unset, {0, 0, 0})}));
  EXPECT_NE(buildError(unset).find("node 1 (blend): input not set"), std::string::npos);

  GraphBuilder shared(threeChannels());
  const NodeIndex p = addPose(shared, {0, 0, 0});
  shared.setRoot(shared.add(BlendNode{.a = p, .b = p}));
  EXPECT_NE(buildError(shared).find("nodes form a tree"), std::string::npos);

  GraphBuilder island(threeChannels());
  addPose(island, {0, 0, 0});
  island.setRoot(addPose(island, {1, 1, 1}));
  EXPECT_NE(buildError(island).find("node 0 (pose): not reachable from the root"), std::string::npos);

  GraphBuilder cycle(threeChannels());
  const NodeIndex root = addPose(cycle, {0, 0, 0});
  const NodeIndex a = cycle.add(BlendNode{.a = 2, .b = addPose(cycle, {0, 0, 0})});  // node 1 -> node 2
  cycle.add(BlendNode{.a = a, .b = addPose(cycle, {0, 0, 0})});                      // node 3 -> node 1
  cycle.setRoot(root);
  EXPECT_FALSE(cycle.build().ok());

  GraphBuilder rootAsInput(threeChannels());
  const NodeIndex r = rootAsInput.add(BlendNode{.a = 0, .b = 1});
  addPose(rootAsInput, {0, 0, 0});
  rootAsInput.setRoot(r);
  EXPECT_NE(buildError(rootAsInput).find("uses the root node as an input"), std::string::npos);
}

TEST(GraphBuilderValidity, ParametersAndNamesMustBeUnique) {
  GraphBuilder twice(threeChannels());
  twice.addFloat("x");
  twice.addTrigger("x");
  twice.setRoot(addPose(twice, {0, 0, 0}));
  EXPECT_NE(buildError(twice).find("/parameters/1: parameter 'x' is declared twice"), std::string::npos);

  GraphBuilder badBool(threeChannels());
  badBool.addParameter("b", ParameterType::Bool, 0.5f);
  badBool.setRoot(addPose(badBool, {0, 0, 0}));
  EXPECT_NE(buildError(badBool).find("bool 'b' default must be 0 or 1"), std::string::npos);

  GraphBuilder names(threeChannels());
  const NodeIndex p0 = names.add(PoseNode{.weights = {0, 0, 0}}, "same");
  const NodeIndex p1 = names.add(PoseNode{.weights = {0, 0, 0}}, "same");
  names.setRoot(names.add(BlendNode{.a = p0, .b = p1}));
  EXPECT_NE(buildError(names).find("node name 'same' is used twice"), std::string::npos);

  GraphBuilder empty(ChannelSet{});
  EXPECT_NE(buildError(empty).find("no channels"), std::string::npos);
}
