// Rig map files (data/rigmaps/*.json): the project's map for RobotExpressive
// loads against the real model's names; malformed maps name file, path, problem.
#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

const std::vector<std::string> kRobotHead = {"Angry", "Surprised", "Sad"};

std::filesystem::path robotMap() { return testing_support::sourceDir() / "data" / "rigmaps" / "RobotExpressive.json"; }

TEST(RigMapFile, ProjectMapDrivesTheRobotsExpressions) {
  auto mapping = loadRigMap(robotMap(), kRobotHead);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Custom);
  EXPECT_NE(mapping->report().detail.find("RobotExpressive.json"), std::string::npos);
  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f), out(3, 0.0f);
  emotions[static_cast<size_t>(Emotion::Fear)] = 1.0f;
  ASSERT_TRUE(mapping->apply(au, emotions, out));
  EXPECT_EQ(out, (std::vector<float>{0.0f, 0.6f, 0.5f}));
  const std::vector<std::string>& unmapped = mapping->report().unmappedInputs;
  for (const char* input : {"happy", "neutral", "AU45_Blink_L"})
    EXPECT_NE(std::find(unmapped.begin(), unmapped.end(), input), unmapped.end()) << input;
}

TEST(RigMapFile, ProjectMapMatchesTheShippedModel) {
  FACIAL_REQUIRE_SHARED();
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / "RobotExpressive.glb");
  ASSERT_TRUE(model) << model.error().message;
  const std::vector<std::string> names = eng::WeightLayout(*model).names();
  auto mapping = buildRigMapping(names, RigMappingOptions{"RobotExpressive", testing_support::sourceDir() / "data" / "rigmaps", {}});
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Custom);
  EXPECT_TRUE(mapping->report().unmappedTargets.empty()) << mapping->report().summary();
}

TEST(RigMapFile, SignedRangeAndSeveralTargetsOfOneName) {
  const std::vector<std::string> names = {"Head/Frown", "Beard/Frown", "Head/Smile"};
  auto mapping = parseRigMap(R"({"version": 1, "weightRange": [-1, 1], "map": {
      "AU12_LipCornerPuller_L": [{"target": "Head/Smile", "weight": 0.5}],
      "AU15_LipCornerDepressor": [{"target": "Head/Frown", "weight": -1}]}})",
                             "signed.json", names);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->minWeight(), -1.0f);
  std::vector<float> au(actionUnits().size(), 0.0f), out(3, 0.0f);
  au[*actionUnitIndex("AU15_LipCornerDepressor")] = 0.5f;
  ASSERT_TRUE(mapping->apply(au, out));
  EXPECT_EQ(out, (std::vector<float>{-0.5f, 0.0f, 0.0f}));
  EXPECT_EQ(mapping->report().unmappedTargets, std::vector<std::string>{"Beard/Frown"});
}

// The fuzzer's seeds (fuzz/seeds/rigmap) load against the fuzzer's target names.
TEST(RigMapFile, FuzzSeedsLoad) {
  const std::vector<std::string> targets = {"Angry", "Surprised", "Sad", "jawOpen", "eyeBlink_L", "eyeBlink_R",
                                            "mouthSmile_L", "mouthSmile_R", "browInnerUp", "target_0"};
  const std::filesystem::path seeds = testing_support::sourceDir() / "fuzz" / "seeds" / "rigmap";
  auto calibration = loadRigMapFile(seeds / "calibration_only.json", targets);
  ASSERT_TRUE(calibration) << calibration.error().message;
  EXPECT_FALSE(calibration->mapping);
  EXPECT_EQ(calibration->calibration.size(), 1u);
  auto both = loadRigMapFile(seeds / "map_and_calibration.json", targets);
  ASSERT_TRUE(both) << both.error().message;
  EXPECT_TRUE(both->mapping);
  EXPECT_EQ(both->calibration.size(), 1u);
}

// ---- the "visemes" block (lip sync) ----

std::vector<float> speakWith(const RigMapping& rig, Viseme viseme) {
  std::vector<float> au(actionUnits().size(), 0.0f), visemes(kVisemeCount, 0.0f), out(rig.targetCount(), 0.0f);
  visemes[size_t(viseme)] = 1.0f;
  auto applied = rig.applyWithVisemes(au, {}, visemes, out);
  EXPECT_TRUE(applied) << applied.error().message;
  return out;
}

const std::vector<std::string> kPuppet = {"Brows", "MouthOpen", "MouthClose", "MouthRound", "JawDown"};

TEST(RigMapFileVisemes, NamedVisemesDriveTheirTargets) {
  auto rig = parseRigMap(R"({"version": 1, "map": {"AU1_InnerBrowRaiser": [{"target": "Brows", "weight": 1}]},
      "visemes": {"aa": {"MouthOpen": 1.0}, "PP": {"MouthClose": 1}, "viseme_O": {"MouthOpen": 0.5, "MouthRound": 1},
                  "u": {"MouthRound": 1}}})",
                         "puppet.json", kPuppet);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->speaks());
  EXPECT_EQ(rig->report().speech, "the rig map's \"visemes\" block");
  EXPECT_EQ(speakWith(*rig, Viseme::aa), (std::vector<float>{0, 1, 0, 0, 0}));
  EXPECT_EQ(speakWith(*rig, Viseme::PP), (std::vector<float>{0, 0, 1, 0, 0}));
  EXPECT_EQ(speakWith(*rig, Viseme::O), (std::vector<float>{0, 0.5f, 0, 1, 0}));
  EXPECT_EQ(speakWith(*rig, Viseme::U), (std::vector<float>{0, 0, 0, 1, 0}));
  EXPECT_EQ(speakWith(*rig, Viseme::sil), (std::vector<float>(5, 0.0f)));  // rest: the neutral mouth
}

// A face with only a jaw: the mouth channels drive it by each viseme's shape.
TEST(RigMapFileVisemes, MouthChannelsDriveEveryVisemeByItsShape) {
  auto rig = parseRigMap(R"({"version": 1, "visemes": {"jawOpen": {"JawDown": 1}, "lipClosure": {"MouthClose": 0.5},
      "lipRounding": {"MouthRound": 1}}})",
                         "jaw.json", kPuppet);
  ASSERT_TRUE(rig) << rig.error().message;
  for (size_t v = 0; v < kVisemeCount; ++v) {
    const std::vector<float> out = speakWith(*rig, Viseme(v));
    const MouthShape& shape = mouthShapeOf(Viseme(v));
    const bool rest = Viseme(v) == Viseme::sil;
    EXPECT_FLOAT_EQ(out[4], rest ? 0.0f : shape.jawOpen) << visemeName(Viseme(v));
    EXPECT_FLOAT_EQ(out[2], rest ? 0.0f : 0.5f * shape.lipClosure) << visemeName(Viseme(v));
    EXPECT_FLOAT_EQ(out[3], rest ? 0.0f : shape.lipRounding) << visemeName(Viseme(v));
  }
  EXPECT_FLOAT_EQ(speakWith(*rig, Viseme::aa)[4], 1.0f);
  EXPECT_FLOAT_EQ(speakWith(*rig, Viseme::PP)[4], 0.0f);
  // No "map": the pose inputs drive nothing, every target is the mouth's.
  EXPECT_EQ(rig->report().unmappedInputs.size(), size_t(rigInputCount()));
}

// A rig map that binds the lip and jaw units speaks through them, as a FACS rig does.
TEST(RigMapFileVisemes, WithoutTheBlockTheMappedJawSpeaks) {
  auto rig = parseRigMap(R"({"version": 1, "map": {"AU26_JawDrop": [{"target": "JawDown", "weight": 1}],
      "AU24_LipPressor": [{"target": "MouthClose", "weight": 1}]}})",
                         "au.json", kPuppet);
  ASSERT_TRUE(rig) << rig.error().message;
  ASSERT_TRUE(rig->speaks()) << rig->report().summary();
  EXPECT_GT(speakWith(*rig, Viseme::aa)[4], 0.7f);
  EXPECT_GT(speakWith(*rig, Viseme::PP)[2], 0.7f);
  EXPECT_FLOAT_EQ(speakWith(*rig, Viseme::PP)[4], 0.0f);
}

// The robot's map binds whole emotions only: nothing moves its mouth, and the
// line says so and where the fix goes.
TEST(RigMapFileVisemes, AMapWithNothingForTheMouthCannotSpeak) {
  auto rig = loadRigMap(robotMap(), kRobotHead);
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_FALSE(rig->speaks());
  const std::string message = cannotSpeakMessage(*rig, "RobotExpressive.glb");
  EXPECT_NE(message.find("RobotExpressive.glb: cannot speak: it has nothing to move the mouth"), std::string::npos)
      << message;
  EXPECT_NE(message.find("\"visemes\""), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

// ---- refused maps ----

std::string rigMapErrorOf(std::string_view json) {
  auto mapping = parseRigMap(json, "bot.json", kRobotHead);
  return mapping ? std::string("(accepted)") : mapping.error().message;
}

TEST(RigMapFileValidity, ErrorsNameFilePathAndProblem) {
  EXPECT_EQ(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Furious", "weight": 1}]}})"),
            "bot.json: /map/anger/0/target: the model has no target 'Furious' (3 targets)");
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"rage": []}})").find("bot.json: /map/rage: unknown channel"),
            std::string::npos);
  EXPECT_EQ(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Angry", "weight": 3}]}})"),
            "bot.json: /map/anger/0/weight: value 3 is outside [-1, 1]");
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Angry", "weight": "full"}]}})")
                .find("bot.json: /map/anger/0/weight: expected a number, got string"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Angry"}]}})").find("bot.json: /map/anger/0: missing \"weight\""),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Angry", "weight": 1, "gain": 2}]}})")
                .find("/map/anger/0/gain: unknown key"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"anger": [{"target": "Angry", "weight": 1}, {"target": "Angry", "weight": 1}]}})")
                .find("/map/anger/1/target: 'Angry' is listed twice"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 2, "map": {}})").find("/version: unsupported version 2"), std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1})").find("bot.json: /: missing \"map\""), std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {}, "maps": {}})").find("/maps: unknown key"), std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "weightRange": [1, 0], "map": {}})").find("/weightRange: min must be below max"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "map": {"anger": {"target": "Angry"}}})").find("bot.json: /map/anger: expected an array, got object"),
            std::string::npos);
}

TEST(RigMapFileValidity, VisemeErrorsNameFilePointerAndProblem) {
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "visemes": {"ah": {"Angry": 1}}})")
                .find("bot.json: /visemes/ah: unknown viseme 'ah' (expected one of sil, PP"),
            std::string::npos);
  EXPECT_EQ(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"MouthOpen": 1}}})"),
            "bot.json: /visemes/aa/MouthOpen: the model has no target 'MouthOpen' (3 targets)");
  EXPECT_EQ(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"Surprised": 2}}})"),
            "bot.json: /visemes/aa/Surprised: value 2 is outside [-1, 1]");
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"Surprised": NaN}}})").find("bot.json"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"Surprised": "open"}}})")
                .find("bot.json: /visemes/aa/Surprised: expected a number, got string"),
            std::string::npos);
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": ["Surprised"]}})").find("bot.json: /visemes/aa: expected an object"),
            std::string::npos);
  EXPECT_EQ(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"Surprised": 0}}})"),
            "bot.json: /visemes: no viseme drives a target (every weight is 0 or the block is empty)");
  EXPECT_NE(rigMapErrorOf(R"({"version": 1, "visemes": {"aa": {"Surprised": 1}}, "calibration": {"AU26_JawDrop": 1}})")
                .find("bot.json: /: \"visemes\" without \"map\""),
            std::string::npos);
}

TEST(RigMapFileValidity, DeepNestingIsRefusedBeforeParsing) {
  // Brackets inside strings (escaped quotes included) do not count; the real depth is 3 + 50,000.
  const std::string deep = R"({"version": 1, "note": "[[[\"{{{", "map": {"anger": )" + std::string(50000, '[') +
                           std::string(50000, ']') + "}}";
  EXPECT_EQ(rigMapErrorOf(deep), "bot.json: JSON nests 50002 levels deep, more than the 256 accepted");
}

TEST(RigMapFileValidity, MissingFileIsNamed) {
  auto mapping = loadRigMap(testing_support::freshTempDir("rigmap_file") / "gone.json", kRobotHead);
  ASSERT_FALSE(mapping);
  EXPECT_NE(mapping.error().message.find("gone.json: file not found"), std::string::npos);
}

}  // namespace
}  // namespace facial
