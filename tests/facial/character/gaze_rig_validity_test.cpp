// Bad input to GazeRig::apply: refused with a message, no weight written.
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/character/gaze_rig.h"

using namespace facial;

namespace {
const std::vector<std::string> kArkitGaze = {"eyeLookInLeft",  "eyeLookOutLeft",  "eyeLookUpLeft",  "eyeLookDownLeft",
                                             "eyeLookInRight", "eyeLookOutRight", "eyeLookUpRight", "eyeLookDownRight"};
}

TEST(GazeRigValidity, WrongWeightCountIsRefused) {
  const GazeRig rig = GazeRig::create(kArkitGaze);
  std::vector<float> w(kArkitGaze.size() - 1, 0.0f);
  auto r = rig.apply({0.1f, 0.0f}, {0.1f, 0.0f}, w);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("7 weights given"), std::string::npos) << r.error().message;
  for (float x : w) EXPECT_EQ(x, 0.0f);
}

TEST(GazeRigValidity, NonFiniteAngleIsRefused) {
  const GazeRig rig = GazeRig::create(kArkitGaze);
  std::vector<float> w(kArkitGaze.size(), 0.0f);
  EXPECT_FALSE(rig.apply({std::numeric_limits<float>::quiet_NaN(), 0.0f}, {}, w));
  for (float x : w) EXPECT_EQ(x, 0.0f);
}

TEST(GazeRigValidity, VrmSetOverOtherTargetsIsNotUsed) {
  VrmExpressionSet vrm;
  vrm.targetNames = {"a", "b"};
  vrm.meshTargetOffsets = {0, 2};
  VrmExpression e;
  e.name = "lookLeft";
  e.group = VrmProceduralGroup::LookAt;
  e.bindCount = 1;
  vrm.expressions.push_back(e);
  vrm.binds.push_back({1, 1.0f});
  const std::vector<std::string> names = {"a", "b", "c"};  // not the layout the VRM addresses
  EXPECT_FALSE(GazeRig::create(names, &vrm).hasVrmExpressions());
}
