// ARKit 52 scheme: both spellings recognised; the AU table drives the shapes
// an animator expects; on Face Cap's real head (../shared/assets/facecap.glb,
// read with eng::loadModel) every basic emotion moves the right shapes.
#include "facial/runtime/rig/arkit_names.h"

#include <algorithm>
#include <map>
#include <ranges>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

std::vector<std::string> canonicalNames() {
  const std::span<const std::string_view> names = arkitBlendShapeNames();
  return {names.begin(), names.end()};
}

// "eyeBlinkLeft" -> "eyeBlink_L" (Face Cap spelling); jawLeft / mouthLeft are not sides.
std::vector<std::string> suffixSpelling() {
  std::vector<std::string> out;
  for (std::string name : canonicalNames()) {
    const bool own = name == "jawLeft" || name == "jawRight" || name == "mouthLeft" || name == "mouthRight";
    if (!own && name.ends_with("Left")) name = name.substr(0, name.size() - 4) + "_L";
    if (!own && name.ends_with("Right")) name = name.substr(0, name.size() - 5) + "_R";
    out.push_back(name);
  }
  return out;
}

// Target weights of `names` for one preset of data/expressions.json at full intensity.
std::map<std::string, float> poseOf(const RigMapping& mapping, std::string_view preset) {
  auto library = ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
  EXPECT_TRUE(library) << library.error().message;
  std::vector<float> au(actionUnits().size());
  EXPECT_TRUE(ExpressionLibrary::evaluate(*library->find(preset), 1.0f, au));
  std::vector<float> weights(mapping.targetCount(), 0.0f);
  EXPECT_TRUE(mapping.apply(au, weights));
  std::map<std::string, float> pose;
  for (size_t t = 0; t < weights.size(); ++t) pose[mapping.targetNames()[t]] = weights[t];
  return pose;
}

TEST(ArkitNames, RecognisesBothSpellingsPrefixesAndCase) {
  ArkitSpelling spelling = ArkitSpelling::Unsided;
  EXPECT_EQ(arkitIndex("eyeBlinkLeft", &spelling), 0u);
  EXPECT_EQ(spelling, ArkitSpelling::LeftRight);
  EXPECT_EQ(arkitIndex("eyeBlink_L", &spelling), 0u);
  EXPECT_EQ(spelling, ArkitSpelling::SuffixLR);
  EXPECT_EQ(arkitIndex("blendShape1.EyeBlink_R"), arkitIndex("eyeBlinkRight"));
  EXPECT_EQ(arkitIndex("jawOpen", &spelling), 17u);
  EXPECT_EQ(spelling, ArkitSpelling::Unsided);
  EXPECT_EQ(arkitBlendShapeNames()[*arkitIndex("jawLeft")], "jawLeft");
  EXPECT_FALSE(arkitIndex("eyeBlink_X"));
  EXPECT_FALSE(arkitIndex("eyeBlinkL"));
  EXPECT_EQ(arkitBlendShapeNames().size(), 52u);
  for (const std::string& name : suffixSpelling()) EXPECT_TRUE(arkitIndex(name)) << name;
}

TEST(ArkitMapping, BothSpellingsGiveTheSameMapping) {
  auto word = buildRigMapping(canonicalNames());
  auto suffix = buildRigMapping(suffixSpelling());
  ASSERT_TRUE(word && suffix);
  EXPECT_EQ(word->scheme(), RigScheme::Arkit52);
  EXPECT_EQ(suffix->scheme(), RigScheme::Arkit52);
  EXPECT_NE(word->report().detail.find("52 of 52 ARKit names, Left/Right spelling"), std::string::npos);
  EXPECT_NE(suffix->report().detail.find("52 of 52 ARKit names, _L/_R spelling"), std::string::npos);
  for (uint32_t input = 0; input < rigInputCount(); ++input) {
    EXPECT_TRUE(std::ranges::equal(word->targets(input), suffix->targets(input))) << rigInputName(input);
    EXPECT_TRUE(std::ranges::equal(word->gains(input), suffix->gains(input))) << rigInputName(input);
  }
}

TEST(ArkitMapping, EveryActionUnitIsMappedAndTheRestIsReported) {
  auto mapping = buildRigMapping(canonicalNames());
  ASSERT_TRUE(mapping);
  for (uint32_t c = 0; c < actionUnits().size(); ++c)  // but AU29: jawForward keeps the model's default
    EXPECT_EQ(mapping->targets(c).empty(), actionUnits()[c].name == "AU29_JawThrust") << actionUnits()[c].name;
  std::vector<std::string> unmapped = mapping->report().unmappedTargets;
  std::sort(unmapped.begin(), unmapped.end());
  const std::vector<std::string> expected = {
      "cheekPuff",        "eyeLookDownLeft", "eyeLookDownRight", "eyeLookInLeft", "eyeLookInRight",
      "eyeLookOutLeft",   "eyeLookOutRight", "eyeLookUpLeft",    "eyeLookUpRight",
      "jawForward",       "jawLeft",          "jawRight",        "mouthClose",       "mouthDimpleLeft", "mouthDimpleRight",
      "mouthLeft",        "mouthRight"};
  EXPECT_EQ(unmapped, expected);
  EXPECT_EQ(mapping->report().unmappedInputs.size(), kEmotionCount + 1);  // AU-level rig: emotions not used; AU29
}

TEST(ArkitMapping, TheTableSendsUnitsToTheirShapes) {
  auto mapping = buildRigMapping(canonicalNames());
  ASSERT_TRUE(mapping);
  auto gain = [&](std::string_view channel, std::string_view shape) {
    const uint32_t input = *actionUnitIndex(channel);
    const uint32_t target = *arkitIndex(shape);
    for (size_t i = 0; i < mapping->targets(input).size(); ++i)
      if (mapping->targets(input)[i] == target) return mapping->gains(input)[i];
    return 0.0f;
  };
  EXPECT_EQ(gain("AU1_InnerBrowRaiser", "browInnerUp"), 1.0f);
  EXPECT_EQ(gain("AU2_OuterBrowRaiser_L", "browOuterUpLeft"), 1.0f);
  EXPECT_EQ(gain("AU2_OuterBrowRaiser_L", "browOuterUpRight"), 0.0f);  // sides stay apart
  EXPECT_EQ(gain("AU4_BrowLowerer", "browDownRight"), 1.0f);
  EXPECT_EQ(gain("AU5_UpperLidRaiser", "eyeWideLeft"), 1.0f);
  EXPECT_EQ(gain("AU6_CheekRaiser", "cheekSquintLeft"), 1.0f);
  EXPECT_EQ(gain("AU7_LidTightener", "eyeSquintRight"), 1.0f);
  EXPECT_EQ(gain("AU9_NoseWrinkler", "noseSneerLeft"), 1.0f);
  EXPECT_EQ(gain("AU10_UpperLipRaiser", "mouthUpperUpRight"), 1.0f);
  EXPECT_EQ(gain("AU12_LipCornerPuller_R", "mouthSmileRight"), 1.0f);
  EXPECT_EQ(gain("AU15_LipCornerDepressor", "mouthFrownLeft"), 1.0f);
  EXPECT_EQ(gain("AU16_LowerLipDepressor", "mouthLowerDownLeft"), 1.0f);
  EXPECT_EQ(gain("AU17_ChinRaiser", "mouthShrugLower"), 1.0f);
  EXPECT_EQ(gain("AU20_LipStretcher", "mouthStretchLeft"), 1.0f);
  EXPECT_EQ(gain("AU24_LipPressor", "mouthPressRight"), 1.0f);
  EXPECT_GT(gain("AU26_JawDrop", "jawOpen"), 0.5f);
  EXPECT_EQ(gain("AU45_Blink_L", "eyeBlinkLeft"), 1.0f);
  EXPECT_EQ(gain("AU45_Blink_L", "eyeBlinkRight"), 0.0f);
}

TEST(ArkitMapping, FaceCapHeadIsDrivenByEveryBasicEmotion) {
  FACIAL_REQUIRE_SHARED();
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / "facecap.glb");
  ASSERT_TRUE(model) << model.error().message;
  const std::vector<std::string> names = eng::WeightLayout(*model).names();
  ASSERT_EQ(names.size(), 52u);
  auto mapping = buildRigMapping(names, RigMappingOptions{"facecap", {}, {}});
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Arkit52);
  EXPECT_NE(mapping->report().detail.find("52 of 52 ARKit names, _L/_R spelling"), std::string::npos);
  EXPECT_EQ(mapping->report().unmappedTargets.size(), 17u);  // mouthFunnel, tongueOut drive AU22, AU19; jawForward keeps its default

  // The shapes that make each emotion read, at full intensity.
  const std::map<std::string, std::vector<std::string>> signature = {
      {"happy", {"mouthSmile_L", "mouthSmile_R", "cheekSquint_L", "cheekSquint_R"}},
      {"sad", {"browInnerUp", "mouthFrown_L", "mouthFrown_R", "mouthShrugLower"}},
      {"surprise", {"browInnerUp", "browOuterUp_L", "browOuterUp_R", "eyeWide_L", "jawOpen"}},
      {"fear", {"browInnerUp", "eyeWide_L", "eyeWide_R", "mouthStretch_L", "mouthStretch_R", "browDown_L"}},
      {"anger", {"browDown_L", "browDown_R", "eyeSquint_L", "eyeSquint_R", "mouthUpperUp_L", "mouthUpperUp_R"}},
      {"disgust", {"noseSneer_L", "noseSneer_R", "mouthUpperUp_L", "mouthFrown_R", "mouthLowerDown_L"}},
  };
  for (const auto& [preset, shapes] : signature) {
    const std::map<std::string, float> pose = poseOf(*mapping, preset);
    for (const std::string& shape : shapes) EXPECT_GE(pose.at(shape), 0.3f) << preset << " / " << shape;
    EXPECT_EQ(pose.at("eyeBlink_L"), 0.0f) << preset;
  }
  // Emotions do not bleed into each other's signature shapes.
  EXPECT_EQ(poseOf(*mapping, "happy").at("mouthFrown_L"), 0.0f);
  EXPECT_EQ(poseOf(*mapping, "sad").at("mouthSmile_L"), 0.0f);
  EXPECT_EQ(poseOf(*mapping, "anger").at("browInnerUp"), 0.0f);
  // A named loop, not views::values over the temporary: clang 14 (the sanitizer
  // build) cannot compile libstdc++ 12's owning_view.
  const std::map<std::string, float> neutral = poseOf(*mapping, "neutral");
  for (const auto& [shape, w] : neutral) EXPECT_EQ(w, 0.0f) << shape;
}

}  // namespace
}  // namespace facial
