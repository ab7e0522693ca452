// VRoid Studio (Fcl_ALL/BRW/EYE/MTH) and viseme (Oculus / Ready Player Me)
// naming schemes on small synthetic target lists: which emotions they drive,
// what fear and disgust are composed of, and that visemes are reported as
// visemes, never as emotions or unmapped shapes.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {
namespace {

// A VRoid face as VRoid Studio exports it (prefixed with the mesh name, as some exporters do).
const std::vector<std::string> kVRoidFace = {
    "Face.M_F00_000_00_Fcl_ALL_Neutral", "Fcl_ALL_Angry", "Fcl_ALL_Fun", "Fcl_ALL_Joy", "Fcl_ALL_Sorrow",
    "Fcl_ALL_Surprised", "Fcl_BRW_Angry", "Fcl_BRW_Fun", "Fcl_BRW_Joy", "Fcl_BRW_Sorrow", "Fcl_BRW_Surprised",
    "Fcl_EYE_Natural", "Fcl_EYE_Angry", "Fcl_EYE_Close", "Fcl_EYE_Close_R", "Fcl_EYE_Close_L", "Fcl_EYE_Joy",
    "Fcl_EYE_Sorrow", "Fcl_EYE_Surprised", "Fcl_MTH_Angry", "Fcl_MTH_Joy", "Fcl_MTH_Sorrow", "Fcl_MTH_Surprised",
    "Fcl_MTH_A", "Fcl_MTH_I", "Fcl_MTH_U", "Fcl_MTH_E", "Fcl_MTH_O", "Fcl_HA_Hide"};

uint32_t indexOf(const std::vector<std::string>& names, std::string_view name) {
  for (uint32_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  ADD_FAILURE() << "no target " << name;
  return 0;
}

float gainOf(const RigMapping& rig, uint32_t input, uint32_t target) {
  const auto targets = rig.targets(input);
  const auto gains = rig.gains(input);
  for (size_t i = 0; i < targets.size(); ++i)
    if (targets[i] == target) return gains[i];
  return 0.0f;
}

bool has(const std::vector<std::string>& list, std::string_view text) {
  return std::any_of(list.begin(), list.end(), [&](const std::string& s) { return s.find(text) != std::string::npos; });
}

TEST(VRoidScheme, WholeFaceEmotionsComposedFearAndDisgustBlinksAndJaw) {
  // The prefix "M_F00_000_00_" is not VRoid's: only the last '.'-separated part counts, so the neutral
  // target is not recognised; the other 28 are.
  auto rig = buildRigMapping(kVRoidFace);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::VRoid);
  EXPECT_NE(rig->report().detail.find("28 of 29 targets are VRoid Fcl_ shapes (5 whole-face ALL"), std::string::npos)
      << rig->report().detail;
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Happy), indexOf(kVRoidFace, "Fcl_ALL_Joy")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Anger), indexOf(kVRoidFace, "Fcl_ALL_Angry")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Sad), indexOf(kVRoidFace, "Fcl_ALL_Sorrow")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Surprise), indexOf(kVRoidFace, "Fcl_ALL_Surprised")), 1.0f);
  // Whole-face shapes win: happy drives only Fcl_ALL_Joy, not its parts too.
  EXPECT_EQ(rig->targets(emotionInput(Emotion::Happy)).size(), 1u);
  // Fear: sorrowful brows over surprised eyes and a milder surprised mouth.
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Fear), indexOf(kVRoidFace, "Fcl_BRW_Sorrow")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Fear), indexOf(kVRoidFace, "Fcl_EYE_Surprised")), 0.8f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Fear), indexOf(kVRoidFace, "Fcl_MTH_Surprised")), 0.45f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Disgust), indexOf(kVRoidFace, "Fcl_BRW_Angry")), 0.7f);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Disgust), indexOf(kVRoidFace, "Fcl_MTH_Angry")), 0.5f);
  EXPECT_TRUE(has(rig->report().emotions, "fear <- 'Fcl_BRW_Sorrow' x0.8") ||
              has(rig->report().emotions, "fear <- 'Fcl_BRW_Sorrow' + 'Fcl_EYE_Surprised' x0.8"))
      << rig->report().summary();
  EXPECT_TRUE(has(rig->report().emotions, "(composed)"));
  // Blinks per side, jaw on the open vowel.
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU45_Blink_L"), indexOf(kVRoidFace, "Fcl_EYE_Close_L")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU45_Blink_R"), indexOf(kVRoidFace, "Fcl_EYE_Close_R")), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU26_JawDrop"), indexOf(kVRoidFace, "Fcl_MTH_A")), 0.7f);
  // The vowels are visemes, not unmapped shapes; Fun is noted.
  EXPECT_EQ(rig->report().visemes,
            (std::vector<std::string>{"Fcl_MTH_A", "Fcl_MTH_I", "Fcl_MTH_U", "Fcl_MTH_E", "Fcl_MTH_O"}));
  EXPECT_FALSE(has(rig->report().unmappedTargets, "Fcl_MTH_I"));
  EXPECT_TRUE(has(rig->report().unmappedTargets, "Fcl_ALL_Fun"));
  EXPECT_TRUE(has(rig->report().notes, "Fun (VRM's relaxed) is not one of the seven emotions"));

  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f), weights(kVRoidFace.size(), 0.0f);
  emotions[size_t(Emotion::Disgust)] = 1.0f;
  ASSERT_TRUE(rig->apply(au, emotions, weights));
  EXPECT_FLOAT_EQ(weights[indexOf(kVRoidFace, "Fcl_EYE_Angry")], 0.6f);
  EXPECT_FLOAT_EQ(weights[indexOf(kVRoidFace, "Fcl_ALL_Angry")], 0.0f);
}

TEST(VRoidScheme, PartsStandInWhenThereAreNoWholeFaceShapes) {
  const std::vector<std::string> parts = {"Fcl_BRW_Joy", "Fcl_EYE_Joy", "Fcl_MTH_Joy", "Fcl_BRW_Angry", "Fcl_EYE_Close"};
  auto rig = buildRigMapping(parts);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::VRoid);
  EXPECT_EQ(rig->targets(emotionInput(Emotion::Happy)).size(), 3u);
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Anger), 3), 1.0f);
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU45_Blink_L"), 4), 0.5f);  // one shape for both eyes
  EXPECT_FLOAT_EQ(gainOf(*rig, emotionInput(Emotion::Disgust), 3), 0.7f);
  EXPECT_TRUE(has(rig->report().emotions, "fear <- nothing")) << rig->report().summary();
}

// Ready Player Me: ARKit's 52 plus the 15 Oculus visemes.
TEST(VisemeNames, ReadyPlayerMeVisemesAreReportedAsVisemesBesideArkit) {
  std::vector<std::string> names;
  for (std::string_view n : arkitBlendShapeNames()) names.emplace_back(n);
  const std::vector<std::string> visemes = {"viseme_sil", "viseme_PP", "viseme_FF", "viseme_TH", "viseme_DD",
                                            "viseme_kk",  "viseme_CH", "viseme_SS", "viseme_nn", "viseme_RR",
                                            "viseme_aa",  "viseme_E",  "viseme_I",  "viseme_O",  "viseme_U"};
  names.insert(names.end(), visemes.begin(), visemes.end());
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Arkit52);
  EXPECT_EQ(rig->report().visemes, visemes);
  for (const std::string& v : visemes) EXPECT_FALSE(has(rig->report().unmappedTargets, v)) << v;
  EXPECT_TRUE(rig->report().emotions.empty()) << "ARKit takes emotions through the action units";
  EXPECT_NE(rig->report().summary().find("visemes (15, lip sync): viseme_sil, viseme_PP"), std::string::npos);
}

TEST(VisemeNames, AVisemeOnlyFaceIsALipSyncRigWithoutEmotions) {
  const std::vector<std::string> names = {"viseme_sil", "viseme_PP", "viseme_aa", "viseme_E", "viseme_O"};
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Visemes);
  for (uint32_t e = 0; e < kEmotionCount; ++e) EXPECT_TRUE(rig->targets(emotionInput(Emotion(e))).empty());
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU26_JawDrop"), 2), 0.7f);
  EXPECT_FLOAT_EQ(gainOf(*rig, *actionUnitIndex("AU24_LipPressor"), 1), 0.6f);
  EXPECT_EQ(rig->report().visemes.size(), 5u);
}

TEST(VisemeNames, RecognisedSpellings) {
  for (const char* name : {"viseme_sil", "VISEME_pp", "Head.viseme_aa", "aa", "oh", "Fcl_MTH_O"})
    EXPECT_TRUE(isVisemeName(name)) << name;
  // Not visemes: emotions, unknown Oculus codes, single letters outside VRM's expressions.
  for (const char* name : {"viseme_happy", "happy", "Fcl_MTH_Joy", "A", "jawOpen", "viseme_"})
    EXPECT_FALSE(isVisemeName(name)) << name;
}

}  // namespace
}  // namespace facial
