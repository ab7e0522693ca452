#include "facial/runtime/character/gaze_rig.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

using namespace facial;

namespace {

const std::vector<std::string> kArkitGazeAndJaw = {
    "jawOpen",        "eyeLookInLeft",   "eyeLookOutLeft", "eyeLookUpLeft",   "eyeLookDownLeft",
    "eyeLookInRight", "eyeLookOutRight", "eyeLookUpRight", "eyeLookDownRight"};

float weightOf(const std::vector<std::string>& names, const std::vector<float>& weights, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return weights[i];
  ADD_FAILURE() << "no target " << name;
  return -1.0f;
}

EyeGaze degrees(float yaw, float pitch) { return {glm::radians(yaw), glm::radians(pitch)}; }

}  // namespace

TEST(GazeRig, ArkitEachEyeLooksInOrOutByItsOwnYaw) {
  const GazeRig rig = GazeRig::create(kArkitGazeAndJaw);
  ASSERT_TRUE(rig.hasArkit());
  EXPECT_EQ(rig.describe(), "ARKit eyeLook*");
  std::vector<float> w(kArkitGazeAndJaw.size(), 0.0f);
  // Both eyes 15 degrees toward the face's left, 6 up.
  ASSERT_TRUE(rig.apply(degrees(15, 6), degrees(15, 6), w));
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookOutLeft"), 0.5f, 1e-5f);
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookInRight"), 0.5f, 1e-5f);
  EXPECT_EQ(weightOf(kArkitGazeAndJaw, w, "eyeLookInLeft"), 0.0f);
  EXPECT_EQ(weightOf(kArkitGazeAndJaw, w, "eyeLookOutRight"), 0.0f);
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookUpLeft"), 0.2f, 1e-5f);
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookUpRight"), 0.2f, 1e-5f);
  EXPECT_EQ(weightOf(kArkitGazeAndJaw, w, "jawOpen"), 0.0f);
}

TEST(GazeRig, ArkitConvergingEyesBothLookIn) {
  const GazeRig rig = GazeRig::create(kArkitGazeAndJaw);
  std::vector<float> w(kArkitGazeAndJaw.size(), 0.0f);
  ASSERT_TRUE(rig.apply(degrees(-9, 0), degrees(9, 0), w));
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookInLeft"), 0.3f, 1e-5f);
  EXPECT_NEAR(weightOf(kArkitGazeAndJaw, w, "eyeLookInRight"), 0.3f, 1e-5f);
}

TEST(GazeRig, AddsToTheGraphsWeightsAndClamps) {
  const GazeRig rig = GazeRig::create(kArkitGazeAndJaw);
  std::vector<float> w(kArkitGazeAndJaw.size(), 0.9f);
  ASSERT_TRUE(rig.apply(degrees(0, -15), degrees(0, -15), w));
  EXPECT_EQ(weightOf(kArkitGazeAndJaw, w, "eyeLookDownLeft"), 1.0f);
  EXPECT_EQ(weightOf(kArkitGazeAndJaw, w, "eyeLookUpLeft"), 0.9f);
}

TEST(GazeRig, ArkitUnderscoreAndPrefixedSpellings) {
  const std::vector<std::string> names = {"blendShape1.eyeLookIn_L", "blendShape1.eyeLookOut_L", "blendShape1.eyeLookUp_L",
                                          "blendShape1.eyeLookDown_L", "blendShape1.eyeLookIn_R", "blendShape1.eyeLookOut_R",
                                          "blendShape1.eyeLookUp_R", "blendShape1.eyeLookDown_R"};
  EXPECT_TRUE(GazeRig::create(names).hasArkit());
}

TEST(GazeRig, HalfAnArkitSetDrivesNothing) {
  const std::vector<std::string> names(kArkitGazeAndJaw.begin(), kArkitGazeAndJaw.begin() + 5);  // left eye only
  const GazeRig rig = GazeRig::create(names);
  EXPECT_FALSE(rig.drivesWeights());
  EXPECT_EQ(rig.describe(), "none");
}

TEST(GazeRig, FacsUnitsFollowBothEyesMean) {
  const std::vector<std::string> names = {"AU12", "AU61_EyesTurnLeft", "AU62_EyesTurnRight", "AU63", "AU64", "AU610"};
  const GazeRig rig = GazeRig::create(names);
  ASSERT_TRUE(rig.hasFacs());
  EXPECT_FALSE(rig.hasArkit());
  std::vector<float> w(names.size(), 0.0f);
  ASSERT_TRUE(rig.apply(degrees(-10, -3), degrees(-20, -3), w));
  EXPECT_EQ(w[1], 0.0f);                 // not left
  EXPECT_NEAR(w[2], 15.0f / 30.0f, 1e-5f);  // right by the mean, 15 degrees
  EXPECT_EQ(w[3], 0.0f);
  EXPECT_NEAR(w[4], 0.1f, 1e-5f);
  EXPECT_EQ(w[0], 0.0f);
  EXPECT_EQ(w[5], 0.0f);  // AU610 is no gaze unit
}

TEST(GazeRig, VrmLookAtExpressionsThroughTheirRangeMaps) {
  VrmExpressionSet vrm;
  vrm.targetNames = {"Face/Fcl_EYE_Look_L", "Face/Fcl_EYE_Look_R", "Face/Fcl_EYE_Look_U", "Face/Fcl_EYE_Look_D"};
  vrm.meshTargetOffsets = {0, 4};
  const char* names[] = {"lookLeft", "lookRight", "lookUp", "lookDown"};
  for (uint32_t i = 0; i < 4; ++i) {
    VrmExpression e;
    e.name = names[i];
    e.isPreset = true;
    e.group = vrmProceduralGroup(names[i]);
    e.firstBind = i;
    e.bindCount = 1;
    vrm.expressions.push_back(e);
    vrm.binds.push_back({i, i == 2 ? 0.5f : 1.0f});
  }
  vrm.lookAt.horizontalOuter = {.inputMaxValue = 20.0f, .outputScale = 1.0f};
  vrm.lookAt.verticalUp = {.inputMaxValue = 10.0f, .outputScale = 0.8f};
  const GazeRig rig = GazeRig::create(vrm.targetNames, &vrm);
  ASSERT_TRUE(rig.hasVrmExpressions());
  std::vector<float> w(4, 0.0f);
  ASSERT_TRUE(rig.apply(degrees(10, 20), degrees(10, 20), w));
  EXPECT_NEAR(w[0], 0.5f, 1e-5f);         // lookLeft: 10 / 20
  EXPECT_EQ(w[1], 0.0f);
  EXPECT_NEAR(w[2], 0.8f * 0.5f, 1e-5f);  // lookUp: clamped at 10 -> 0.8, bind weight 0.5
  EXPECT_EQ(w[3], 0.0f);

  vrm.lookAt.type = VrmLookAtType::Bone;  // eye bones: the joints take the gaze, no weights
  EXPECT_FALSE(GazeRig::create(vrm.targetNames, &vrm).drivesWeights());
}
