#include "facial/runtime/graph/nodes/additive_node.h"

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

// Base: every AU at 0.5; layer: every AU at 0.3; mask and weight under test.
std::vector<float> layered(RegionMask mask, float weight) {
  const uint32_t n = static_cast<uint32_t>(actionUnits().size());
  GraphBuilder b(ChannelSet::actionUnits());
  const NodeIndex base = addPose(b, std::vector<float>(n, 0.5f));
  const NodeIndex layer = addPose(b, std::vector<float>(n, 0.3f));
  b.setRoot(b.add(AdditiveNode{.base = base, .layer = layer, .weight = FloatInput::fixed(weight), .mask = mask}));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.016f);
  return {face.weights().begin(), face.weights().end()};
}

}  // namespace

TEST(AdditiveNode, UpperFaceMaskAddsOnlyToUpperFaceUnits) {
  const std::vector<float> w = layered({.region = FaceRegion::Upper}, 1.0f);
  for (size_t c = 0; c < w.size(); ++c)
    EXPECT_FLOAT_EQ(w[c], actionUnits()[c].region == FaceRegion::Upper ? 0.8f : 0.5f) << actionUnits()[c].name;
}

TEST(AdditiveNode, LowerLeftMaskNeedsBothRegionAndSide) {
  const std::vector<float> w = layered({.region = FaceRegion::Lower, .side = FaceSide::Left}, 0.5f);
  for (size_t c = 0; c < w.size(); ++c) {
    const bool pass = actionUnits()[c].region == FaceRegion::Lower && actionUnits()[c].side == FaceSide::Left;
    EXPECT_FLOAT_EQ(w[c], pass ? 0.65f : 0.5f) << actionUnits()[c].name;
  }
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU12_LipCornerPuller_L")], 0.65f);
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU12_LipCornerPuller_R")], 0.5f);
}

TEST(AdditiveNode, RightSideMaskSkipsBilateralUnits) {
  const std::vector<float> w = layered({.side = FaceSide::Right}, 1.0f);
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU45_Blink_R")], 0.8f);
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU2_OuterBrowRaiser_R")], 0.8f);
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU45_Blink_L")], 0.5f);
  EXPECT_FLOAT_EQ(w[*actionUnitIndex("AU26_JawDrop")], 0.5f);
}

TEST(AdditiveNode, ResultIsClampedToZeroOne) {
  const std::vector<float> w = layered({}, 3.0f);  // 0.5 + 3 * 0.3 = 1.4
  for (float v : w) EXPECT_FLOAT_EQ(v, 1.0f);
  const std::vector<float> negative = layered({}, -4.0f);
  for (float v : negative) EXPECT_FLOAT_EQ(v, 0.0f);
}

TEST(AdditiveNode, RawTargetNamesOfUnknownRegionPassOnlyAnyRegion) {
  const std::vector<std::string> names = {"eyeBlink_L", "jawOpen"};
  GraphBuilder b(ChannelSet::fromNames(names).value());
  const NodeIndex base = addPose(b, {0.1f, 0.1f});
  const NodeIndex layer = addPose(b, {0.5f, 0.5f});
  b.setRoot(b.add(AdditiveNode{.base = base, .layer = layer, .mask = {.region = FaceRegion::Upper}}));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  EXPECT_FLOAT_EQ(face.weights()[0], 0.1f);
  EXPECT_FLOAT_EQ(face.weights()[1], 0.1f);
}

TEST(AdditiveNodeValidity, WeightParameterMustExist) {
  GraphBuilder b(threeChannels());
  const NodeIndex base = addPose(b, {0, 0, 0}), layer = addPose(b, {0, 0, 0});
  b.setRoot(b.add(AdditiveNode{.base = base, .layer = layer, .weight = FloatInput::bound(0)}));
  EXPECT_NE(buildError(b).find("/weight: parameter index 0 out of range"), std::string::npos);
}
