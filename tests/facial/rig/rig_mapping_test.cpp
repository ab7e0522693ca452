// RigMapping: the sparse layout and apply(); scheme detection for FACS-named
// and expression-named rigs; the report of what is not mapped; refused calls.
#include "facial/runtime/rig/rig_mapping.h"

#include <algorithm>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

uint32_t au(std::string_view name) { return *actionUnitIndex(name); }

bool contains(const std::vector<std::string>& list, std::string_view item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

struct Buffers {
  std::vector<float> au = std::vector<float>(actionUnits().size(), 0.0f);
  std::vector<float> emotions = std::vector<float>(kEmotionCount, 0.0f);
};

TEST(RigInputs, LayoutIsActionUnitsThenEmotions) {
  EXPECT_EQ(rigInputCount(), actionUnits().size() + kEmotionCount);
  EXPECT_EQ(rigInputIndex("AU4_BrowLowerer"), actionUnitIndex("AU4_BrowLowerer"));
  EXPECT_EQ(rigInputIndex("anger"), emotionInput(Emotion::Anger));
  EXPECT_EQ(rigInputName(emotionInput(Emotion::Disgust)), "disgust");
  EXPECT_FALSE(rigInputIndex("AU4"));
}

TEST(RigMappingBuilder, LaysOutRowsAndAccumulatesRepeatedEntries) {
  const std::vector<std::string> targets = {"a", "b", "c"};
  RigMappingBuilder builder(RigScheme::Custom, targets);
  builder.add(au("AU4_BrowLowerer"), 2, 0.5f);
  builder.add(au("AU1_InnerBrowRaiser"), 0, 1.0f);
  builder.add(au("AU4_BrowLowerer"), 2, 0.25f);  // repeat: gains add
  builder.add(emotionInput(Emotion::Sad), 0, 0.3f);
  auto mapping = builder.build();
  ASSERT_TRUE(mapping) << mapping.error().message;
  ASSERT_TRUE(mapping->validate());
  ASSERT_EQ(mapping->targets(au("AU4_BrowLowerer")).size(), 1u);
  EXPECT_FLOAT_EQ(mapping->gains(au("AU4_BrowLowerer"))[0], 0.75f);
  EXPECT_EQ(mapping->drivenTargets().size(), 2u);
  EXPECT_EQ(mapping->report().unmappedTargets, std::vector<std::string>{"b"});
  EXPECT_EQ(mapping->report().unmappedInputs.size(), rigInputCount() - 3);
  EXPECT_TRUE(contains(mapping->report().unmappedInputs, "AU12_LipCornerPuller_L"));
  EXPECT_TRUE(mapping->targets(rigInputCount()).empty());  // out of range: empty row
}

TEST(RigMapping, ApplySumsClampsAndLeavesUndrivenTargetsAlone) {
  const std::vector<std::string> targets = {"smile", "identity", "frown"};
  RigMappingBuilder builder(RigScheme::Custom, targets);
  builder.add(au("AU12_LipCornerPuller_L"), 0, 0.6f);
  builder.add(au("AU12_LipCornerPuller_R"), 0, 0.6f);
  builder.add(au("AU15_LipCornerDepressor"), 2, 1.0f);
  builder.add(emotionInput(Emotion::Sad), 2, 0.5f);
  auto mapping = builder.build();
  ASSERT_TRUE(mapping);
  Buffers in;
  in.au[au("AU12_LipCornerPuller_L")] = 0.5f;
  in.au[au("AU12_LipCornerPuller_R")] = 1.0f;
  std::vector<float> out = {9.0f, 0.42f, 9.0f};
  ASSERT_TRUE(mapping->apply(in.au, out));
  EXPECT_FLOAT_EQ(out[0], 0.9f);
  EXPECT_FLOAT_EQ(out[1], 0.42f);  // not driven: untouched
  EXPECT_FLOAT_EQ(out[2], 0.0f);   // driven but at rest: reset, not left at 9
  in.au[au("AU15_LipCornerDepressor")] = 0.8f;
  in.emotions[static_cast<size_t>(Emotion::Sad)] = 1.0f;
  ASSERT_TRUE(mapping->apply(in.au, in.emotions, out));
  EXPECT_FLOAT_EQ(out[2], 1.0f);  // 0.8 + 0.5 clamped
}

TEST(RigMappingDetection, ChannelNamedTargetsMapByIdentity) {
  std::vector<std::string> targets;
  for (const ActionUnitInfo& info : actionUnits()) targets.emplace_back(info.name);
  targets.push_back("tongueOut");
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::ActionUnits);
  for (uint32_t c = 0; c < actionUnits().size(); ++c) {
    ASSERT_EQ(mapping->targets(c).size(), 1u) << actionUnits()[c].name;
    EXPECT_EQ(mapping->targets(c)[0], c);
    EXPECT_FLOAT_EQ(mapping->gains(c)[0], 1.0f);
  }
  EXPECT_EQ(mapping->report().unmappedTargets, std::vector<std::string>{"tongueOut"});
  // The emotion channels drive nothing on an AU rig, and say so.
  EXPECT_EQ(mapping->report().unmappedInputs.size(), kEmotionCount);
}

TEST(RigMappingDetection, FacsNumberedTargetsSplitAndMergeSides) {
  const std::vector<std::string> targets = {"AU01", "au12_L", "AU12_R", "AU45", "AU2 Outer brow", "AU14_Dimpler"};
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::ActionUnits);
  Buffers in;
  in.au[au("AU1_InnerBrowRaiser")] = 0.8f;
  in.au[au("AU12_LipCornerPuller_L")] = 1.0f;
  in.au[au("AU45_Blink_L")] = 1.0f;  // a wink on a bilateral blink target reaches half
  in.au[au("AU2_OuterBrowRaiser_L")] = 1.0f;
  in.au[au("AU2_OuterBrowRaiser_R")] = 1.0f;
  std::vector<float> out(targets.size(), 0.0f);
  ASSERT_TRUE(mapping->apply(in.au, out));
  EXPECT_FLOAT_EQ(out[0], 0.8f);
  EXPECT_FLOAT_EQ(out[1], 1.0f);
  EXPECT_FLOAT_EQ(out[2], 0.0f);
  EXPECT_FLOAT_EQ(out[3], 0.5f);
  EXPECT_FLOAT_EQ(out[4], 1.0f);
  // AU14 is not in the channel vocabulary: reported, not guessed.
  EXPECT_EQ(mapping->report().unmappedTargets, std::vector<std::string>{"AU14_Dimpler"});
}

TEST(RigMappingDetection, EmotionNamedTargetsTakeTheEmotionChannels) {
  // RobotExpressive's Head mesh.
  const std::vector<std::string> targets = {"Angry", "Surprised", "Sad"};
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Expressions);
  Buffers in;
  in.emotions[static_cast<size_t>(Emotion::Anger)] = 0.7f;
  std::vector<float> out(3, 0.0f);
  ASSERT_TRUE(mapping->apply(in.au, in.emotions, out));
  EXPECT_EQ(out, (std::vector<float>{0.7f, 0.0f, 0.0f}));
  // Fear and disgust are approximated from the expressions the robot has, and the report says so.
  in.emotions = std::vector<float>(kEmotionCount, 0.0f);
  in.emotions[static_cast<size_t>(Emotion::Fear)] = 1.0f;
  ASSERT_TRUE(mapping->apply(in.au, in.emotions, out));
  EXPECT_FLOAT_EQ(out[1], 0.55f);
  EXPECT_FLOAT_EQ(out[2], 0.45f);
  const RigMappingReport& report = mapping->report();
  EXPECT_TRUE(std::any_of(report.notes.begin(), report.notes.end(), [](const std::string& n) {
    return n.find("fear: the rig has no such expression; approximated as 'Surprised' 0.55 + 'Sad' 0.45") !=
           std::string::npos;
  })) << report.summary();
  // No happy or neutral target, no blink: reported.
  EXPECT_TRUE(contains(report.unmappedInputs, "happy"));
  EXPECT_TRUE(contains(report.unmappedInputs, "neutral"));
  EXPECT_TRUE(contains(report.unmappedInputs, "AU45_Blink_L"));
  EXPECT_TRUE(report.unmappedTargets.empty());
  EXPECT_NE(report.summary().find("scheme: emotion expressions (VRM)"), std::string::npos) << report.summary();
}

// VRM 0.x has no surprised preset: such an avatar (its presets only) shows
// surprise by its vowel O's round open mouth, and fear, composed from
// surprise and sorrow, opens it too. Before, surprise moved nothing.
TEST(RigMappingDetection, AVrm0AvatarWithoutSurpriseOpensItsMouthRound) {
  const std::vector<std::string> targets = {"neutral", "a", "i", "u", "e", "o", "blink", "joy", "angry", "sorrow", "fun"};
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Expressions);
  Buffers in;
  std::vector<float> out(targets.size(), 0.0f);
  in.emotions[static_cast<size_t>(Emotion::Surprise)] = 1.0f;
  ASSERT_TRUE(mapping->apply(in.au, in.emotions, out));
  EXPECT_FLOAT_EQ(out[5], 0.8f);
  EXPECT_FLOAT_EQ(out[9], 0.0f);
  in.emotions = std::vector<float>(kEmotionCount, 0.0f);
  in.emotions[static_cast<size_t>(Emotion::Fear)] = 1.0f;
  ASSERT_TRUE(mapping->apply(in.au, in.emotions, out));
  EXPECT_FLOAT_EQ(out[5], 0.44f);
  EXPECT_FLOAT_EQ(out[9], 0.45f);
  const RigMappingReport& report = mapping->report();
  for (const char* note : {"surprise: the rig has no such expression; approximated as 'o' 0.8 (the round open mouth)",
                           "fear: the rig has no such expression; approximated as 'o' 0.44 + 'sorrow' 0.45"})
    EXPECT_TRUE(std::any_of(report.notes.begin(), report.notes.end(),
                            [&](const std::string& n) { return n.find(note) != std::string::npos; }))
        << note << "\n" << report.summary();
  EXPECT_FALSE(contains(report.unmappedInputs, "surprise"));
}

TEST(RigMappingDetection, SameNameOnSeveralMeshesDrivesAll) {
  const std::vector<std::string> targets = {"Face.blink", "Lashes.blink", "Face.joy"};
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  Buffers in;
  in.au[au("AU45_Blink_L")] = 1.0f;
  in.au[au("AU45_Blink_R")] = 1.0f;
  std::vector<float> out(3, 0.0f);
  ASSERT_TRUE(mapping->apply(in.au, out));
  EXPECT_EQ(out, (std::vector<float>{1.0f, 1.0f, 0.0f}));
}

// A report names each target once, however many meshes carry it (a Ready
// Player Me avatar has its visemes on the head, the teeth and the beard).
TEST(RigMappingDetection, ReportNamesATargetOnSeveralMeshesOnce) {
  const std::vector<std::string> targets = {"viseme_aa", "custom", "viseme_aa", "custom", "viseme_O"};
  auto mapping = buildRigMapping(targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->report().visemes, (std::vector<std::string>{"viseme_aa", "viseme_O"}));
  EXPECT_EQ(mapping->report().unmappedTargets, std::vector<std::string>{"custom"});
  EXPECT_NE(mapping->report().summary().find("visemes (2, lip sync): viseme_aa, viseme_O\n"), std::string::npos)
      << mapping->report().summary();
}

TEST(RigMappingDetection, RigMapFileInTheDirectoryWinsOverDetection) {
  const std::filesystem::path dir = testing_support::freshTempDir("rigmap_detection");
  testing_support::writeFile(dir / "bot.json",
                             R"({"version": 1, "map": {"happy": [{"target": "Sad", "weight": 0.1}]}})");
  const std::vector<std::string> targets = {"Angry", "Surprised", "Sad"};
  auto mapping = buildRigMapping(targets, RigMappingOptions{"bot", dir, {}});
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Custom);
  // Another model name finds no file and falls back to detection.
  auto detected = buildRigMapping(targets, RigMappingOptions{"other", dir, {}});
  ASSERT_TRUE(detected);
  EXPECT_EQ(detected->scheme(), RigScheme::Expressions);
}

// ---- refused input ----

TEST(RigMappingValidity, NoSchemeSuggestsARigMapFile) {
  const std::vector<std::string> targets = {"Key 1", "Key 2", "Key 3"};
  auto mapping = buildRigMapping(targets, RigMappingOptions{"MorphStressTest", {}, {}});
  ASSERT_FALSE(mapping);
  EXPECT_EQ(mapping.error().message,
            "rig mapping: no scheme recognises the 3 target names of 'MorphStressTest' (Key 1, Key 2, Key 3, ...); "
            "write a rig map data/rigmaps/MorphStressTest.json");
  auto forced = buildRigMapping(targets, RigScheme::Arkit52);
  ASSERT_FALSE(forced);
  EXPECT_NE(forced.error().message.find("ARKit 52 blend shapes scheme recognises none of the 3"), std::string::npos);
  EXPECT_FALSE(buildRigMapping(targets, RigScheme::Custom));
}

TEST(RigMappingValidity, ApplyNamesWrongSizesAndNonFiniteWeights) {
  auto mapping = buildRigMapping(std::vector<std::string>{"AU4_BrowLowerer", "AU1_InnerBrowRaiser", "AU5_UpperLidRaiser"});
  ASSERT_TRUE(mapping);
  Buffers in;
  std::vector<float> out(3, 0.0f), shortOut(2, 0.0f);
  auto wrongTargets = mapping->apply(in.au, shortOut);
  ASSERT_FALSE(wrongTargets);
  EXPECT_NE(wrongTargets.error().message.find("2 target weights; expected " + std::to_string(actionUnits().size()) +
                                              ", 0 or 7, 3"),
            std::string::npos)
      << wrongTargets.error().message;
  const std::vector<float> shortAu(4, 0.0f);
  EXPECT_FALSE(mapping->apply(shortAu, out));
  const std::vector<float> badEmotions(3, 0.0f);
  EXPECT_FALSE(mapping->apply(in.au, badEmotions, out));
  in.au[au("AU5_UpperLidRaiser")] = std::numeric_limits<float>::infinity();
  out = {0.3f, 0.3f, 0.3f};
  auto nonFinite = mapping->apply(in.au, out);
  ASSERT_FALSE(nonFinite);
  EXPECT_NE(nonFinite.error().message.find("AU weight AU5_UpperLidRaiser is not finite"), std::string::npos);
  EXPECT_EQ(out, (std::vector<float>{0.3f, 0.3f, 0.3f}));  // nothing written
}

TEST(RigMappingValidity, BuilderRefusesOutOfRangeEntries) {
  const std::vector<std::string> targets = {"a"};
  RigMappingBuilder badTarget(RigScheme::Custom, targets);
  badTarget.add(0, 4, 1.0f);
  auto r = badTarget.build();
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("target 4 of 1"), std::string::npos) << r.error().message;
  RigMappingBuilder badInput(RigScheme::Custom, targets);
  badInput.add(rigInputCount(), 0, 1.0f);
  EXPECT_FALSE(badInput.build());
  RigMappingBuilder badGain(RigScheme::Custom, targets);
  badGain.add(0, 0, std::numeric_limits<float>::quiet_NaN());
  EXPECT_FALSE(badGain.build());
  RigMappingBuilder badRange(RigScheme::Custom, targets);
  badRange.setWeightRange(1.0f, 0.0f);
  EXPECT_FALSE(badRange.build());
}

}  // namespace
}  // namespace facial
