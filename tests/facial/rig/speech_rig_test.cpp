// The viseme block of rig mappings (rig_mapping.h, "Viseme block"): every
// scheme realises the 15 visemes, on small synthetic target lists; a face
// with nothing that moves the mouth cannot speak. Ready Player Me's avatar
// (../shared/speech/rpm-visemes.glb) when the shared folder is there.
#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/candide_units.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

const std::vector<std::string> kOculus = {"viseme_sil", "viseme_PP", "viseme_FF", "viseme_TH", "viseme_DD",
                                          "viseme_kk",  "viseme_CH", "viseme_SS", "viseme_nn", "viseme_RR",
                                          "viseme_aa",  "viseme_E",  "viseme_I",  "viseme_O",  "viseme_U"};

uint32_t indexOf(std::span<const std::string> names, std::string_view name) {
  for (uint32_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  ADD_FAILURE() << "no target " << name;
  return 0;
}

std::vector<float> speak(const RigMapping& rig, Viseme viseme, std::vector<float> emotions = {}) {
  std::vector<float> au(actionUnits().size(), 0.0f), visemes(kVisemeCount, 0.0f), out(rig.targetCount(), 0.0f);
  visemes[size_t(viseme)] = 1.0f;
  auto applied = rig.applyWithVisemes(au, emotions, visemes, out);
  EXPECT_TRUE(applied) << applied.error().message;
  return out;
}

float weightOf(const RigMapping& rig, const std::vector<float>& out, std::string_view name) {
  return out[indexOf(rig.targetNames(), name)];
}

TEST(RigVisemeInputs, NamesAndCommonSpellings) {
  EXPECT_EQ(rigVisemeInputName(Viseme::PP), "viseme_PP");
  EXPECT_EQ(rigVisemeInputName(Viseme::sil), "viseme_sil");
  for (const char* name : {"viseme_PP", "PP", "pp", "VISEME_pp"}) EXPECT_EQ(rigVisemeIndex(name), Viseme::PP) << name;
  EXPECT_EQ(rigVisemeIndex("aa"), Viseme::aa);
  EXPECT_FALSE(rigVisemeIndex("viseme_happy"));
  EXPECT_FALSE(rigVisemeIndex("AU26_JawDrop"));
  // The pose layout is untouched by the viseme block.
  EXPECT_EQ(rigInputCount(), actionUnits().size() + kEmotionCount);
}

TEST(SpeechRig, OculusVisemesAreDrivenByIdentityBesideArkit) {
  std::vector<std::string> names;
  for (std::string_view n : arkitBlendShapeNames()) names.emplace_back(n);
  names.insert(names.end(), kOculus.begin(), kOculus.end());
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Arkit52);
  ASSERT_TRUE(rig->speaks());
  // Each viseme drives its own target; rest also meets the lips (a part of
  // PP) and the rounded ones ease a smile (mouthSmile, negative).
  for (size_t v = 0; v < kVisemeCount; ++v) {
    const auto targets = rig->visemeTargets(Viseme(v));
    const auto gains = rig->visemeGains(Viseme(v));
    for (size_t i = 0; i < targets.size(); ++i) {
      const std::string& name = names[targets[i]];
      if (name == kOculus[v]) EXPECT_FLOAT_EQ(gains[i], 1.0f);
      else if (Viseme(v) == Viseme::sil) EXPECT_EQ(name, "viseme_PP");
      else EXPECT_TRUE(name.starts_with("mouthSmile") && gains[i] < 0.0f) << visemeName(Viseme(v)) << " -> " << name;
    }
  }
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::sil), "viseme_PP"), 0.2f);
  const std::vector<float> out = speak(*rig, Viseme::PP);
  EXPECT_FLOAT_EQ(weightOf(*rig, out, "viseme_PP"), 1.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, out, "viseme_aa"), 0.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, out, "jawOpen"), 0.0f);  // the visemes speak, not the ARKit mouth too
  EXPECT_NE(rig->report().summary().find("speech: 15 of 15 Oculus viseme targets, identity"), std::string::npos)
      << rig->report().summary();
}

TEST(SpeechRig, AVisemeOnlyFaceBorrowsTheClosestShapeForMissingVisemes) {
  const std::vector<std::string> names = {"viseme_sil", "viseme_PP", "viseme_aa", "viseme_E", "viseme_O"};
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Visemes);
  ASSERT_EQ(rig->visemeTargets(Viseme::U).size(), 1u);
  EXPECT_EQ(rig->visemeTargets(Viseme::U)[0], 4u);  // U borrows O (rounded)
  EXPECT_EQ(rig->visemeTargets(Viseme::FF)[0], 1u);  // FF borrows PP (lip closure)
  EXPECT_NE(rig->report().speech.find("U <- O"), std::string::npos) << rig->report().speech;
  // Without visemes apply() leaves viseme targets alone, as before the viseme block.
  std::vector<float> au(actionUnits().size(), 0.0f), out(names.size(), 0.5f);
  ASSERT_TRUE(rig->apply(au, out));
  EXPECT_FLOAT_EQ(out[4], 0.5f);
}

// A VRM 1.0 face: happy (binds the smile, with the given overrideMouth) and the five vowels.
std::shared_ptr<VrmExpressionSet> vrmVowelFace(VrmOverride happyOverridesMouth) {
  auto set = std::make_shared<VrmExpressionSet>();
  set->targetNames = {"Face/smile", "Face/A", "Face/I", "Face/U", "Face/E", "Face/O"};
  set->meshTargetOffsets = {0, 6};
  auto add = [&](std::string name, VrmProceduralGroup group, uint32_t target, VrmOverride overrideMouth) {
    VrmExpression e;
    e.name = std::move(name);
    e.isPreset = true;
    e.group = group;
    e.overrideMouth = overrideMouth;
    e.firstBind = static_cast<uint32_t>(set->binds.size());
    e.bindCount = 1;
    set->binds.push_back({target, 1.0f});
    set->expressions.push_back(e);
  };
  add("happy", VrmProceduralGroup::None, 0, happyOverridesMouth);
  add("aa", VrmProceduralGroup::Mouth, 1, VrmOverride::None);
  add("ih", VrmProceduralGroup::Mouth, 2, VrmOverride::None);
  add("ou", VrmProceduralGroup::Mouth, 3, VrmOverride::None);
  add("ee", VrmProceduralGroup::Mouth, 4, VrmOverride::None);
  add("oh", VrmProceduralGroup::Mouth, 5, VrmOverride::None);
  return set;
}

std::vector<float> happyAt(float weight) {
  std::vector<float> emotions(kEmotionCount, 0.0f);
  emotions[size_t(Emotion::Happy)] = weight;
  return emotions;
}

TEST(SpeechRig, VrmVowelExpressionsThroughTheStage) {
  auto set = vrmVowelFace(VrmOverride::None);
  auto rig = buildVrmRigMapping(set, set->targetNames);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->speaks()) << rig->report().summary();
  EXPECT_NE(rig->report().speech.find("VRM 1.0"), std::string::npos);
  std::vector<float> out = speak(*rig, Viseme::O);
  EXPECT_FLOAT_EQ(out[5], 1.0f);
  EXPECT_FLOAT_EQ(out[1], 0.0f);
  EXPECT_GT(speak(*rig, Viseme::CH)[3], 0.3f);  // CH rounds: some "ou"
  out = speak(*rig, Viseme::aa, happyAt(1.0f));  // no override: both show
  EXPECT_FLOAT_EQ(out[0], 1.0f);
  EXPECT_FLOAT_EQ(out[1], 1.0f);
}

// UniVRM / VRM 1.0: an expression's overrideMouth acts on the mouth group
// (the vowels) while it shows: block silences it, blend scales it by 1 - weight.
TEST(SpeechRig, VrmOverrideMouthOfTheEmotionHoldsOverTheVowels) {
  auto blocking = vrmVowelFace(VrmOverride::Block);
  auto block = buildVrmRigMapping(blocking, blocking->targetNames);
  ASSERT_TRUE(block) << block.error().message;
  std::vector<float> out = speak(*block, Viseme::aa, happyAt(1.0f));
  EXPECT_FLOAT_EQ(out[0], 1.0f);
  EXPECT_FLOAT_EQ(out[1], 0.0f);
  EXPECT_FLOAT_EQ(speak(*block, Viseme::aa)[1], 1.0f);  // without the emotion the vowel shows
  auto blending = vrmVowelFace(VrmOverride::Blend);
  auto blend = buildVrmRigMapping(blending, blending->targetNames);
  ASSERT_TRUE(blend) << blend.error().message;
  out = speak(*blend, Viseme::aa, happyAt(0.25f));
  EXPECT_FLOAT_EQ(out[0], 0.25f);
  EXPECT_FLOAT_EQ(out[1], 0.75f);
}

// Many VRMs bind 'aa' alone (the shared test avatars do): the empty vowels
// borrow it at their own jaw opening instead of leaving the mouth still.
TEST(SpeechRig, VrmVowelsThatBindNothingBorrowTheOpenVowel) {
  auto set = vrmVowelFace(VrmOverride::None);
  for (size_t e = 2; e < set->expressions.size(); ++e) set->expressions[e].bindCount = 0;  // ih ou ee oh
  auto rig = buildVrmRigMapping(set, set->targetNames);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_NE(rig->report().speech.find("1 of 5 vowels"), std::string::npos) << rig->report().speech;
  EXPECT_NE(rig->report().speech.find("ee <- aa x0.55"), std::string::npos) << rig->report().speech;
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::aa)[1], 1.0f);
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::E)[1], 0.55f);
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::O)[1], 0.6f);
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::I)[1], 0.3f);
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::PP)[1], 0.0f);
  EXPECT_FLOAT_EQ(speak(*rig, Viseme::sil)[1], 0.0f);
}

TEST(SpeechRig, VRoidMouthVowelsAndClose) {
  const std::vector<std::string> names = {"Fcl_ALL_Joy",  "Fcl_EYE_Close", "Fcl_MTH_A", "Fcl_MTH_I",
                                          "Fcl_MTH_U",    "Fcl_MTH_E",     "Fcl_MTH_O", "Fcl_MTH_Close"};
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::VRoid);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::aa), "Fcl_MTH_A"), 1.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::I), "Fcl_MTH_I"), 1.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::U), "Fcl_MTH_U"), 1.0f);
  const std::vector<float> pp = speak(*rig, Viseme::PP);
  EXPECT_FLOAT_EQ(weightOf(*rig, pp, "Fcl_MTH_Close"), 1.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, pp, "Fcl_MTH_A"), 0.0f);
  EXPECT_NE(rig->report().speech.find("closed mouth for PP"), std::string::npos);
}

TEST(SpeechRig, ArkitOnlyFaceComposesVisemesFromMouthShapes) {
  std::vector<std::string> names;
  for (std::string_view n : arkitBlendShapeNames()) names.emplace_back(n);
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->speaks());
  const std::vector<float> pp = speak(*rig, Viseme::PP);
  EXPECT_GT(weightOf(*rig, pp, "mouthPressLeft"), 0.4f);
  EXPECT_GT(weightOf(*rig, pp, "mouthPressRight"), 0.4f);
  EXPECT_FLOAT_EQ(weightOf(*rig, pp, "jawOpen"), 0.0f);
  const std::vector<float> ff = speak(*rig, Viseme::FF);
  EXPECT_GT(weightOf(*rig, ff, "mouthRollLower"), 0.5f);
  const std::vector<float> u = speak(*rig, Viseme::U);
  EXPECT_GT(weightOf(*rig, u, "mouthPucker"), 0.8f);
  const std::vector<float> o = speak(*rig, Viseme::O);
  EXPECT_GT(weightOf(*rig, o, "mouthFunnel"), 0.6f);
  const std::vector<float> aa = speak(*rig, Viseme::aa);
  EXPECT_GT(weightOf(*rig, aa, "jawOpen"), weightOf(*rig, o, "jawOpen"));
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::TH), "tongueOut"), 0.3f);
  EXPECT_TRUE(speak(*rig, Viseme::sil) == std::vector<float>(names.size(), 0.0f));
  EXPECT_NE(rig->report().speech.find("ARKit mouth shapes"), std::string::npos);
}

// A happy face cannot pucker through a full smile: rounded visemes take back
// part of the smile through the rig's AU12 rows; unrounded ones leave it.
TEST(SpeechRig, RoundedVisemesEaseTheSmile) {
  std::vector<std::string> names;
  for (std::string_view n : arkitBlendShapeNames()) names.emplace_back(n);
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  std::vector<float> au(actionUnits().size(), 0.0f), visemes(kVisemeCount, 0.0f), out(names.size(), 0.0f);
  au[*actionUnitIndex("AU12_LipCornerPuller_L")] = au[*actionUnitIndex("AU12_LipCornerPuller_R")] = 0.75f;
  auto smileAt = [&](Viseme v) {
    std::fill(visemes.begin(), visemes.end(), 0.0f);
    visemes[size_t(v)] = 1.0f;
    EXPECT_TRUE(rig->applyWithVisemes(au, {}, visemes, out));
    return weightOf(*rig, out, "mouthSmileLeft");
  };
  const float open = smileAt(Viseme::aa), rounded = smileAt(Viseme::U), half = smileAt(Viseme::O);
  EXPECT_GT(open, 0.5f);
  EXPECT_LT(rounded, open - 0.4f);
  EXPECT_GT(rounded, 0.0f);
  EXPECT_LT(half, open - 0.2f);
  EXPECT_GT(half, rounded);
  // Without a smile the rounded viseme writes no negative weight (clamped at 0).
  std::fill(au.begin(), au.end(), 0.0f);
  EXPECT_FLOAT_EQ(smileAt(Viseme::U), 0.0f);
}

TEST(SpeechRig, ActionUnitHeadComposesVisemesFromLipAndJawUnits) {
  std::vector<std::string> names;
  for (const ActionUnitInfo& unit : actionUnits()) names.emplace_back(unit.name);
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::ActionUnits);
  ASSERT_TRUE(rig->speaks());
  const std::vector<float> pp = speak(*rig, Viseme::PP);
  EXPECT_GT(weightOf(*rig, pp, "AU24_LipPressor"), 0.7f);
  EXPECT_FLOAT_EQ(weightOf(*rig, pp, "AU26_JawDrop"), 0.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, pp, "AU25_LipsPart"), 0.0f);
  const std::vector<float> aa = speak(*rig, Viseme::aa);
  EXPECT_FLOAT_EQ(weightOf(*rig, aa, "AU26_JawDrop"), 1.0f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::U), "AU18_LipPucker"), 0.8f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::O), "AU22_LipFunneler"), 0.6f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::CH), "AU22_LipFunneler"), 0.4f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::U), "AU23_LipTightener"), 0.0f);  // rounding is pucker and funnel here
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::TH), "AU19_TongueShow"), 1.0f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::DD), "AU19_TongueShow"), 0.3f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::I), "AU20_LipStretcher"), 0.5f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::aa), "AU4_BrowLowerer"), 0.0f);
  EXPECT_TRUE(speak(*rig, Viseme::sil) == std::vector<float>(names.size(), 0.0f));  // rest: the neutral mouth
}

TEST(SpeechRig, AnActionUnitFaceWithoutPuckerOrFunnelRoundsWithTheLipTightener) {
  // Older FACS rigs have no AU18/AU22/AU19/AU27/AU28: rounding falls back to
  // AU23, and what has no fallback (the tongue) is simply absent.
  std::vector<std::string> names;
  const std::vector<int> lacking = {18, 19, 22, 27, 28};
  for (const ActionUnitInfo& unit : actionUnits())
    if (std::ranges::find(lacking, unit.facsNumber) == lacking.end()) names.emplace_back(unit.name);
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::ActionUnits);
  ASSERT_TRUE(rig->speaks());
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::U), "AU23_LipTightener"), 0.9f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::O), "AU23_LipTightener"), 0.6f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::CH), "AU23_LipTightener"), 0.4f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::O), "AU26_JawDrop"), 0.6f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::aa), "AU26_JawDrop"), 1.0f);
  const std::vector<float> th = speak(*rig, Viseme::TH);
  EXPECT_GT(weightOf(*rig, th, "AU25_LipsPart"), 0.5f);
  EXPECT_EQ(std::count_if(th.begin(), th.end(), [](float w) { return w > 0.0f; }), 2);  // lips part and jaw, no tongue
}

TEST(SpeechRig, CalibrationKeepsTheVisemeBlock) {
  std::vector<std::string> names;
  for (const ActionUnitInfo& unit : actionUnits()) names.emplace_back(unit.name);
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  auto calibrated = calibrateRig(*rig, std::vector<float>(names.size(), 0.01f));
  ASSERT_TRUE(calibrated) << calibrated.error().message;
  ASSERT_TRUE(calibrated->rig.speaks());
  for (size_t v = 0; v < kVisemeCount; ++v) {
    EXPECT_TRUE(std::ranges::equal(calibrated->rig.visemeTargets(Viseme(v)), rig->visemeTargets(Viseme(v))));
    EXPECT_TRUE(std::ranges::equal(calibrated->rig.visemeGains(Viseme(v)), rig->visemeGains(Viseme(v))));
  }
  EXPECT_EQ(calibrated->rig.report().speech, rig->report().speech);
}

TEST(SpeechRig, Candide3SpeaksThroughItsAnimationUnits) {
  std::vector<std::string> names;
  for (const CandideAnimationUnit& unit : candideAnimationUnits()) names.push_back(candideTargetName(unit));
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Candide3);
  ASSERT_TRUE(rig->speaks());
  const std::string jaw = candideTargetName(*findCandideUnit("Jaw drop"));
  const std::string presser = candideTargetName(*findCandideUnit("Lip presser"));
  const std::string stretcher = candideTargetName(*findCandideUnit("Lip stretcher"));
  const std::string depressor = candideTargetName(*findCandideUnit("Lip corner depressor"));
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::aa), jaw), 0.7f);
  EXPECT_GT(weightOf(*rig, speak(*rig, Viseme::PP), presser), 0.8f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::PP), jaw), 0.0f);
  // No pucker on the mask: rounded visemes draw the corners in (the stretcher
  // backwards), and leave the signed smile (a negative depressor) alone.
  EXPECT_LT(weightOf(*rig, speak(*rig, Viseme::U), stretcher), -0.5f);
  EXPECT_LT(weightOf(*rig, speak(*rig, Viseme::O), stretcher), -0.3f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::aa), stretcher), 0.0f);
  EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::U), depressor), 0.0f);
  for (const std::string& target : names) EXPECT_FLOAT_EQ(weightOf(*rig, speak(*rig, Viseme::sil), target), 0.0f);
}

TEST(SpeechRig, AFaceWithNothingToMoveTheMouthCannotSpeak) {
  const std::vector<std::string> names = {"eyeBlinkLeft", "eyeBlinkRight", "browInnerUp", "browDownLeft",
                                          "browDownRight", "eyeWideLeft", "eyeWideRight", "eyeSquintLeft",
                                          "eyeSquintRight", "cheekSquintLeft", "cheekSquintRight"};
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_FALSE(rig->speaks());
  EXPECT_NE(rig->report().summary().find("speech: none"), std::string::npos);
  const std::string message = cannotSpeakMessage(*rig, "'brows'");
  EXPECT_NE(message.find("'brows': cannot speak"), std::string::npos) << message;
  EXPECT_NE(message.find("none of its 11 targets"), std::string::npos) << message;
  EXPECT_NE(message.find("viseme_*"), std::string::npos) << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0);
}

TEST(SpeechRigValidity, VisemeWeightsAreCheckedAndBuilderRefusesBadVisemeEntries) {
  std::vector<std::string> names = kOculus;
  auto rig = buildRigMapping(names);
  ASSERT_TRUE(rig);
  std::vector<float> au(actionUnits().size(), 0.0f), out(names.size(), 0.25f), few(3, 0.0f);
  auto wrongSize = rig->applyWithVisemes(au, {}, few, out);
  ASSERT_FALSE(wrongSize);
  EXPECT_NE(wrongSize.error().message.find("3 viseme weights; expected 0 or 15"), std::string::npos);
  std::vector<float> nan(kVisemeCount, 0.0f);
  nan[3] = std::numeric_limits<float>::quiet_NaN();
  auto notFinite = rig->applyWithVisemes(au, {}, nan, out);
  ASSERT_FALSE(notFinite);
  EXPECT_NE(notFinite.error().message.find("viseme_TH is not finite"), std::string::npos);
  EXPECT_EQ(out, std::vector<float>(names.size(), 0.25f));  // nothing written
  RigMappingBuilder bad(RigScheme::Custom, names);
  bad.addViseme(Viseme::PP, 99, 1.0f);
  EXPECT_FALSE(bad.build());
}

TEST(SpeechRig, ReadyPlayerMeAvatarSpeaks) {
  FACIAL_REQUIRE_SHARED();
  auto model = eng::loadModel(testing_support::sharedDir() / "speech" / "rpm-visemes.glb");
  ASSERT_TRUE(model) << model.error().message;
  const std::vector<std::string> names = eng::WeightLayout(*model).names();
  auto rig = buildRigMapping(names, RigMappingOptions{"rpm-visemes", {}, {}});
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->speaks()) << rig->report().summary();
  for (size_t v = 0; v < kVisemeCount; ++v) EXPECT_FALSE(rig->visemeTargets(Viseme(v)).empty()) << visemeName(Viseme(v));
  EXPECT_NE(rig->report().speech.find("15 of 15 Oculus"), std::string::npos) << rig->report().summary();
}

}  // namespace
}  // namespace facial
