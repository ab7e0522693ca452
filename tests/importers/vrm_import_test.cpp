// VRM import: small VRM 1.0 / 0.x documents written by the test (as .gltf
// JSON and as a binary .vrm container) become VrmExpressionSets; emotions
// drive them through a rig mapping; malformed extensions are refused with
// file + JSON path + problem.
#include "importers/vrm_import.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/scene/glb_container.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "tests/common/test_support.h"
#include "tests/importers/shared_vrm.h"

namespace facial {
namespace {

// One face mesh (4 targets) on node 1, a teeth mesh (1 target) on node 2, node 0 without mesh.
Json vrm1Document() {
  return Json::parse(R"({
    "asset": {"version": "2.0"},
    "nodes": [{"name": "root"}, {"name": "face", "mesh": 0}, {"name": "teeth", "mesh": 1}],
    "materials": [{"name": "skin"}, {"name": "eye"}],
    "meshes": [
      {"name": "Face", "primitives": [{"attributes": {}, "targets": [{}, {}, {}, {}]},
                                      {"attributes": {}, "targets": [{}, {}, {}, {}]}],
       "extras": {"targetNames": ["Fcl_Joy", "Fcl_Blink", "Fcl_Angry", "Fcl_A"]}},
      {"primitives": [{"attributes": {}, "targets": [{}]}]}
    ],
    "extensionsUsed": ["VRMC_vrm"],
    "extensions": {"VRMC_vrm": {"specVersion": "1.0", "expressions": {
      "preset": {
        "happy": {"morphTargetBinds": [{"node": 1, "index": 0, "weight": 1.0}], "overrideBlink": "block",
                  "materialColorBinds": [{"material": 0, "type": "color", "targetValue": [1, 0, 0, 1]}]},
        "blink": {"morphTargetBinds": [{"node": 1, "index": 1, "weight": 1.0}]},
        "angry": {"morphTargetBinds": [{"node": 1, "index": 2, "weight": 0.8}], "overrideBlink": "blend",
                  "overrideMouth": "block"},
        "aa": {"morphTargetBinds": [{"node": 1, "index": 3, "weight": 1.0}, {"node": 2, "index": 0, "weight": 0.5}]},
        "neutral": {}
      },
      "custom": {"smirk": {"isBinary": true, "morphTargetBinds": [{"node": 1, "index": 0, "weight": 0.4}]}}
    }}}
  })");
}

Json vrm0Document() {
  return Json::parse(R"({
    "asset": {"version": "2.0"},
    "nodes": [{"mesh": 0}],
    "materials": [{"name": "skin"}, {"name": "eye"}],
    "meshes": [{"name": "Body", "primitives": [{"attributes": {}, "targets": [{}, {}, {}, {}, {}]}]}],
    "extensions": {"VRM": {"blendShapeMaster": {"blendShapeGroups": [
      {"name": "Joy", "presetName": "joy", "binds": [{"mesh": 0, "index": 0, "weight": 100}]},
      {"name": "Sorrow", "presetName": "sorrow", "binds": [{"mesh": 0, "index": 1, "weight": 60}]},
      {"name": "Blink_L", "presetName": "blink_l", "binds": [{"mesh": 0, "index": 2, "weight": 100}]},
      {"name": "Blink_R", "presetName": "blink_r", "binds": [{"mesh": 0, "index": 3, "weight": 100}]},
      {"name": "Wink", "presetName": "unknown", "isBinary": true, "binds": [{"mesh": 0, "index": 4, "weight": 100}],
       "materialValues": [{"materialName": "eye", "propertyName": "_Color", "targetValue": [1, 1, 1, 1]}]}
    ]}}}
  })");
}

size_t expressionIndex(const VrmExpressionSet& set, std::string_view name) {
  for (size_t i = 0; i < set.expressions.size(); ++i)
    if (set.expressions[i].name == name) return i;
  ADD_FAILURE() << "no expression " << name;
  return 0;
}

TEST(VrmImport, ReadsVrm1PresetAndCustomExpressions) {
  auto set = importers::importVrmExpressions(vrm1Document(), "avatar.gltf");
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_EQ(set->specVersion, 1);
  EXPECT_EQ(set->expressionNames(), (std::vector<std::string>{"happy", "blink", "angry", "aa", "neutral", "smirk"}));
  EXPECT_EQ(set->targetNames, (std::vector<std::string>{"Face/Fcl_Joy", "Face/Fcl_Blink", "Face/Fcl_Angry",
                                                        "Face/Fcl_A", "mesh_1/target_0"}));
  EXPECT_EQ(set->meshTargetOffsets, (std::vector<uint32_t>{0, 4, 5}));
  const VrmExpression& happy = set->expressions[expressionIndex(*set, "happy")];
  EXPECT_TRUE(happy.isPreset);
  EXPECT_EQ(happy.overrideBlink, VrmOverride::Block);
  EXPECT_EQ(happy.overrideMouth, VrmOverride::None);
  const VrmExpression& angry = set->expressions[expressionIndex(*set, "angry")];
  EXPECT_EQ(angry.overrideBlink, VrmOverride::Blend);
  EXPECT_EQ(angry.overrideMouth, VrmOverride::Block);
  EXPECT_FLOAT_EQ(set->binds[angry.firstBind].weight, 0.8f);
  const VrmExpression& aa = set->expressions[expressionIndex(*set, "aa")];
  EXPECT_EQ(aa.group, VrmProceduralGroup::Mouth);
  ASSERT_EQ(aa.bindCount, 2u);
  EXPECT_EQ(set->binds[aa.firstBind + 1].target, 4u);  // node 2 -> mesh 1 -> flat target 4
  const VrmExpression& smirk = set->expressions[expressionIndex(*set, "smirk")];
  EXPECT_FALSE(smirk.isPreset);
  EXPECT_TRUE(smirk.isBinary);
  EXPECT_EQ(set->expressions[expressionIndex(*set, "blink")].group, VrmProceduralGroup::Blink);
  EXPECT_TRUE(set->warnings.empty());
  EXPECT_EQ(set->materialCount, 2u);
  ASSERT_EQ(happy.materialColorBindCount, 1u);
  const VrmMaterialColorBind& red = set->materialColorBinds[happy.firstMaterialColorBind];
  EXPECT_EQ(red.material, 0u);
  EXPECT_EQ(red.type, VrmMaterialColorType::Color);
  EXPECT_EQ(red.targetValue, (std::array<float, 4>{1, 0, 0, 1}));
}

TEST(VrmImport, ReadsVrm0GroupsWithPercentWeights) {
  auto set = importers::importVrmExpressions(vrm0Document(), "old.vrm");
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_EQ(set->specVersion, 0);
  EXPECT_EQ(set->expressionNames(), (std::vector<std::string>{"joy", "sorrow", "blink_l", "blink_r", "Wink"}));
  EXPECT_FLOAT_EQ(set->binds[set->expressions[1].firstBind].weight, 0.6f);
  EXPECT_EQ(set->expressions[2].group, VrmProceduralGroup::Blink);
  EXPECT_FALSE(set->expressions[4].isPreset);
  EXPECT_TRUE(set->expressions[4].isBinary);
  EXPECT_TRUE(set->warnings.empty());
  ASSERT_EQ(set->expressions[4].materialColorBindCount, 1u);
  EXPECT_EQ(set->materialColorBinds[0].material, 1u);  // by name: "eye"
}

TEST(VrmImport, LoadsTextAndBinaryFiles) {
  const std::filesystem::path dir = testing_support::freshTempDir("vrm_import");
  const std::string json = vrm1Document().dump();
  testing_support::writeFile(dir / "avatar.gltf", json);
  const std::vector<uint8_t> glb = eng::buildGlb(json, {});
  testing_support::writeFile(dir / "avatar.vrm", std::string(glb.begin(), glb.end()));
  for (const char* file : {"avatar.gltf", "avatar.vrm"}) {
    auto set = importers::loadVrmExpressions(dir / file);
    ASSERT_TRUE(set) << set.error().message;
    EXPECT_EQ(set->expressions.size(), 6u) << file;
  }
}

// The fuzzer's seeds (fuzz/seeds/vrm) are well-formed VRM 1.0 and 0.x documents.
TEST(VrmImport, FuzzSeedsLoad) {
  const std::filesystem::path seeds = testing_support::sourceDir() / "fuzz" / "seeds" / "vrm";
  for (const char* file : {"vrm1_triangle.gltf", "vrm0_triangle.gltf"}) {
    auto set = importers::loadVrmExpressions(seeds / file);
    ASSERT_TRUE(set) << set.error().message;
    EXPECT_FALSE(set->expressions.empty()) << file;
  }
}

TEST(VrmImport, EmotionPresetsDriveVrmExpressionsWithOverrides) {
  auto set = importers::importVrmExpressions(vrm1Document(), "avatar.gltf");
  ASSERT_TRUE(set) << set.error().message;
  const std::vector<std::string> names = set->expressionNames();
  auto mapping = buildRigMapping(names);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Expressions);

  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f);
  std::vector<float> expressionWeights(names.size(), 0.0f), morph(set->targetCount(), 0.0f);
  auto drive = [&] {
    ASSERT_TRUE(mapping->apply(au, emotions, expressionWeights));
    ASSERT_TRUE(set->apply(expressionWeights, morph));
  };
  // A blink alone closes the eyes (AU45 both sides -> blink).
  au[*actionUnitIndex("AU45_Blink_L")] = 1.0f;
  au[*actionUnitIndex("AU45_Blink_R")] = 1.0f;
  drive();
  EXPECT_FLOAT_EQ(morph[1], 1.0f);
  // Happy (overrideBlink block) suppresses the same blink.
  emotions[static_cast<size_t>(Emotion::Happy)] = 0.7f;
  drive();
  EXPECT_FLOAT_EQ(expressionWeights[expressionIndex(*set, "happy")], 0.7f);
  EXPECT_FLOAT_EQ(morph[0], 0.7f);
  EXPECT_FLOAT_EQ(morph[1], 0.0f);
  // Anger blends the blink down instead.
  emotions[static_cast<size_t>(Emotion::Happy)] = 0.0f;
  emotions[static_cast<size_t>(Emotion::Anger)] = 0.25f;
  drive();
  EXPECT_FLOAT_EQ(morph[1], 0.75f);
  EXPECT_FLOAT_EQ(morph[2], 0.2f);
}

TEST(VrmImport, Vrm0PresetNamesMapToEmotions) {
  auto set = importers::importVrmExpressions(vrm0Document(), "old.vrm");
  ASSERT_TRUE(set);
  auto mapping = buildRigMapping(set->expressionNames());
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Expressions);
  ASSERT_EQ(mapping->targets(emotionInput(Emotion::Happy)).size(), 1u);
  EXPECT_EQ(mapping->targets(emotionInput(Emotion::Happy))[0], 0u);  // joy
  EXPECT_EQ(mapping->targets(emotionInput(Emotion::Sad))[0], 1u);    // sorrow
  EXPECT_EQ(mapping->targets(*actionUnitIndex("AU45_Blink_L"))[0], 2u);
  EXPECT_EQ(mapping->targets(*actionUnitIndex("AU45_Blink_R"))[0], 3u);
  EXPECT_NE(std::find(mapping->report().unmappedTargets.begin(), mapping->report().unmappedTargets.end(), "Wink"),
            mapping->report().unmappedTargets.end());
}

// ---- refused documents ----

std::string errorOf(const Json& document) {
  auto set = importers::importVrmExpressions(document, "bad.vrm");
  return set ? std::string("(accepted)") : set.error().message;
}

TEST(VrmImport, ReadsTheLookAtTypeAndRangeMaps) {
  auto plain = importers::importVrmExpressions(vrm1Document(), "face.vrm");
  ASSERT_TRUE(plain) << plain.error().message;
  EXPECT_EQ(plain->lookAt.type, VrmLookAtType::Expression);  // the defaults without a lookAt
  EXPECT_EQ(plain->lookAt.horizontalOuter.inputMaxValue, 90.0f);
  EXPECT_EQ(plain->lookAt.horizontalOuter.outputScale, 1.0f);

  Json doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["lookAt"] = Json::parse(R"({"type": "bone",
      "rangeMapHorizontalOuter": {"inputMaxValue": 45, "outputScale": 12},
      "rangeMapVerticalUp": {"inputMaxValue": 30}})");
  auto bone = importers::importVrmExpressions(doc, "bone.vrm");
  ASSERT_TRUE(bone) << bone.error().message;
  EXPECT_EQ(bone->lookAt.type, VrmLookAtType::Bone);
  EXPECT_EQ(bone->lookAt.horizontalOuter.inputMaxValue, 45.0f);
  EXPECT_EQ(bone->lookAt.horizontalOuter.outputScale, 12.0f);
  EXPECT_EQ(bone->lookAt.verticalUp.inputMaxValue, 30.0f);
  EXPECT_EQ(bone->lookAt.verticalUp.outputScale, 10.0f);  // bone outputs are degrees, 10 by default
  EXPECT_FLOAT_EQ(bone->lookAt.horizontalOuter.map(90.0f), 12.0f);
  EXPECT_FLOAT_EQ(bone->lookAt.horizontalOuter.map(-22.5f), 6.0f);

  Json vrm0 = vrm0Document();
  vrm0["extensions"]["VRM"]["firstPerson"] = Json::parse(R"({"lookAtTypeName": "BlendShape",
      "lookAtHorizontalOuter": {"curve": [0, 0, 0, 1, 1, 1, 1, 0], "xRange": 20, "yRange": 0.8}})");
  auto blendShape = importers::importVrmExpressions(vrm0, "old.vrm");
  ASSERT_TRUE(blendShape) << blendShape.error().message;
  EXPECT_EQ(blendShape->lookAt.type, VrmLookAtType::Expression);
  EXPECT_EQ(blendShape->lookAt.horizontalOuter.inputMaxValue, 20.0f);
  EXPECT_FLOAT_EQ(blendShape->lookAt.horizontalOuter.outputScale, 0.8f);
}

TEST(VrmImportValidity, LookAtFieldsAreChecked) {
  Json doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["lookAt"] = Json::parse(R"({"type": "eyes"})");
  EXPECT_EQ(errorOf(doc), "bad.vrm: /extensions/VRMC_vrm/lookAt/type: must be \"bone\" or \"expression\", got \"eyes\"");
  doc["extensions"]["VRMC_vrm"]["lookAt"] = Json::parse(R"({"rangeMapVerticalDown": {"inputMaxValue": 0}})");
  EXPECT_NE(errorOf(doc).find("lookAt/rangeMapVerticalDown/inputMaxValue: must be a number in (0, 180], got 0"),
            std::string::npos)
      << errorOf(doc);
  doc["extensions"]["VRMC_vrm"]["lookAt"] = Json::parse(R"({"rangeMapVerticalDown": {"outputScale": "big"}})");
  EXPECT_NE(errorOf(doc).find("rangeMapVerticalDown/outputScale: must be a number in [0, 1e6]"), std::string::npos);
  Json vrm0 = vrm0Document();
  vrm0["extensions"]["VRM"]["firstPerson"] = Json::parse(R"({"lookAtTypeName": 3})");
  EXPECT_NE(errorOf(vrm0).find("/extensions/VRM/firstPerson/lookAtTypeName: must be \"Bone\" or \"BlendShape\""),
            std::string::npos)
      << errorOf(vrm0);
}

TEST(VrmImportValidity, BindsAreCheckedAgainstTheDocument) {
  Json doc = vrm1Document();
  Json& happyBind = doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["happy"]["morphTargetBinds"][0];
  happyBind["index"] = 7;
  EXPECT_EQ(errorOf(doc), "bad.vrm: /extensions/VRMC_vrm/expressions/preset/happy/morphTargetBinds/0/index: "
                          "7 is out of range (4 morph targets on mesh 0)");
  happyBind["index"] = 0;
  happyBind["weight"] = 1.5;
  EXPECT_NE(errorOf(doc).find("happy/morphTargetBinds/0/weight: weight 1.5 is outside [0, 1]"), std::string::npos)
      << errorOf(doc);
  happyBind["weight"] = 1.0;
  happyBind["node"] = 0;  // the root node has no mesh
  EXPECT_NE(errorOf(doc).find("happy/morphTargetBinds/0/node: node 0 has no mesh"), std::string::npos);
  happyBind["node"] = 9;
  EXPECT_NE(errorOf(doc).find("node: 9 is out of range (3 nodes)"), std::string::npos);
  happyBind["node"] = "face";
  EXPECT_NE(errorOf(doc).find("node: must be a non-negative integer"), std::string::npos);
}

TEST(VrmImportValidity, FieldsAreCheckedByType) {
  Json doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["angry"]["overrideBlink"] = "sometimes";
  EXPECT_NE(errorOf(doc).find("preset/angry/overrideBlink: must be \"none\", \"block\" or \"blend\", got \"sometimes\""),
            std::string::npos);
  doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["blink"]["isBinary"] = "yes";
  EXPECT_NE(errorOf(doc).find("preset/blink/isBinary: expected true or false, got string"), std::string::npos);
  doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["expressions"]["custom"]["happy"] = Json::object();
  EXPECT_NE(errorOf(doc).find("custom/happy: a custom expression must not reuse the preset name"), std::string::npos);
  doc = vrm1Document();
  doc["meshes"][0]["primitives"][1]["targets"] = Json::array({Json::object()});
  EXPECT_NE(errorOf(doc).find("/meshes/0/primitives/1/targets: 1 morph targets, primitive 0 has 4"),
            std::string::npos);
}

TEST(VrmImportValidity, Vrm0WeightsRunToOneHundredAndPresetsAreKnown) {
  Json doc = vrm0Document();
  Json& group = doc["extensions"]["VRM"]["blendShapeMaster"]["blendShapeGroups"][1];
  group["binds"][0]["weight"] = 150;
  EXPECT_NE(errorOf(doc).find("blendShapeGroups/1/binds/0/weight: weight 150 is outside [0, 100]"),
            std::string::npos)
      << errorOf(doc);
  group["binds"][0]["weight"] = 50;
  group["binds"][0]["mesh"] = 3;
  EXPECT_NE(errorOf(doc).find("binds/0/mesh: 3 is out of range (1 meshes)"), std::string::npos);
  group["binds"][0]["mesh"] = 0;
  group["presetName"] = "grin";
  EXPECT_NE(errorOf(doc).find("blendShapeGroups/1/presetName: 'grin' is not a VRM 0.x preset name"), std::string::npos);
}

TEST(VrmImportValidity, NonVrmAndBrokenFilesAreNamed) {
  EXPECT_EQ(errorOf(Json::parse(R"({"asset": {"version": "2.0"}})")),
            "bad.vrm: /: no VRMC_vrm (VRM 1.0) or VRM (VRM 0.x) extension: not a VRM model");
  const std::filesystem::path dir = testing_support::freshTempDir("vrm_import_bad");
  std::vector<uint8_t> glb = eng::buildGlb(vrm1Document().dump(), {});
  glb.resize(glb.size() / 2);  // truncated container
  testing_support::writeFile(dir / "cut.vrm", std::string(glb.begin(), glb.end()));
  auto cut = importers::loadVrmExpressions(dir / "cut.vrm");
  ASSERT_FALSE(cut);
  EXPECT_NE(cut.error().message.find("cut.vrm: truncated GLB"), std::string::npos) << cut.error().message;
  testing_support::writeFile(dir / "half.gltf", "{\"extensions\": {");
  auto half = importers::loadVrmExpressions(dir / "half.gltf");
  ASSERT_FALSE(half);
  EXPECT_NE(half.error().message.find("half.gltf: invalid JSON"), std::string::npos) << half.error().message;
  auto missing = importers::loadVrmExpressions(dir / "absent.vrm");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("absent.vrm: file not found"), std::string::npos);
}

}  // namespace
}  // namespace facial

// ---- the VRM rig: expressions as an expression stage of the rig mapping ----
namespace facial {
namespace {

std::shared_ptr<const VrmExpressionSet> sharedSet(const Json& document) {
  auto set = importers::importVrmExpressions(document, "avatar.vrm");
  if (!set) {
    ADD_FAILURE() << set.error().message;
    return nullptr;
  }
  return std::make_shared<const VrmExpressionSet>(std::move(*set));
}

std::vector<std::string> morphNames(const VrmExpressionSet& set) {
  std::vector<std::string> names;
  for (const std::string& n : set.targetNames) names.push_back(n.substr(n.find('/') + 1));
  return names;
}

bool contains(const std::vector<std::string>& list, std::string_view text) {
  return std::any_of(list.begin(), list.end(), [&](const std::string& s) { return s.find(text) != std::string::npos; });
}

TEST(VrmRig, EmotionsReachMorphTargetsThroughTheExpressionBindsAndOverrides) {
  auto set = sharedSet(vrm1Document());
  ASSERT_TRUE(set);
  auto rig = buildVrmRigMapping(set, morphNames(*set));
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::Expressions);
  EXPECT_EQ(rig->targetCount(), 5u);  // the morph targets, not the 6 expressions
  EXPECT_EQ(rig->controlNames().size(), 6u);
  ASSERT_NE(rig->expressionStage(), nullptr);

  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f), morph(5, -1.0f);
  au[*actionUnitIndex("AU45_Blink_L")] = 1.0f;
  au[*actionUnitIndex("AU45_Blink_R")] = 1.0f;
  ASSERT_TRUE(rig->apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[1], 1.0f);  // blink
  EXPECT_FLOAT_EQ(morph[0], 0.0f);
  EXPECT_FLOAT_EQ(morph[3], -1.0f);  // aa: no input drives the mouth; left as it was
  emotions[size_t(Emotion::Happy)] = 0.7f;  // happy blocks the blink
  ASSERT_TRUE(rig->apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[0], 0.7f);
  EXPECT_FLOAT_EQ(morph[1], 0.0f);
  emotions[size_t(Emotion::Happy)] = 0.0f;
  emotions[size_t(Emotion::Anger)] = 0.25f;  // angry blends it down
  ASSERT_TRUE(rig->apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[1], 0.75f);
  EXPECT_FLOAT_EQ(morph[2], 0.2f);

  const RigMappingReport& report = rig->report();
  EXPECT_NE(report.stage.find("VRM 1.0 expressions, 6 expressions over 5 morph targets"), std::string::npos)
      << report.stage;
  EXPECT_NE(report.stage.find("1 material colour"), std::string::npos) << report.stage;
  EXPECT_EQ(report.visemes, (std::vector<std::string>{"aa"}));
  EXPECT_TRUE(contains(report.emotions, "happy <- 'happy'"));
  EXPECT_TRUE(contains(report.emotions, "fear <- nothing")) << report.summary();
  EXPECT_TRUE(contains(report.emotions, "disgust <- 'angry' x0.5 (composed)")) << report.summary();
  EXPECT_TRUE(contains(report.notes, "expressions that bind nothing (no visible change on this model): 'neutral'"))
      << report.summary();
  EXPECT_EQ(report.unmappedControls, (std::vector<std::string>{"smirk"}));
  EXPECT_NE(report.summary().find("emotion surprise <- nothing"), std::string::npos) << report.summary();
}

TEST(VrmRig, BinaryExpressionsSnapAndACopyAppliesIndependently) {
  Json doc = vrm1Document();
  doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["happy"]["isBinary"] = true;
  auto set = sharedSet(doc);
  ASSERT_TRUE(set);
  auto rig = buildVrmRigMapping(set, morphNames(*set));
  ASSERT_TRUE(rig) << rig.error().message;
  const RigMapping copy = *rig;
  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f), morph(5, 0.0f);
  emotions[size_t(Emotion::Happy)] = 0.4f;
  ASSERT_TRUE(rig->apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[0], 0.0f);
  emotions[size_t(Emotion::Happy)] = 0.6f;
  ASSERT_TRUE(copy.apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[0], 1.0f);
}

TEST(VrmRig, RelaxedStandsInForAMissingHappyAndFearIsComposed) {
  Json doc = vrm1Document();
  Json& presets = doc["extensions"]["VRMC_vrm"]["expressions"]["preset"];
  presets["relaxed"] = presets["happy"];
  presets.erase("happy");
  presets["surprised"] = Json::parse(R"({"morphTargetBinds": [{"node": 1, "index": 3, "weight": 1.0}]})");
  presets["sad"] = Json::parse(R"({"morphTargetBinds": [{"node": 1, "index": 2, "weight": 0.5}]})");
  auto set = sharedSet(doc);
  ASSERT_TRUE(set);
  auto rig = buildVrmRigMapping(set, morphNames(*set));
  ASSERT_TRUE(rig) << rig.error().message;
  const RigMappingReport& report = rig->report();
  EXPECT_TRUE(contains(report.emotions, "happy <- 'relaxed'")) << report.summary();
  EXPECT_TRUE(contains(report.emotions, "fear <- 'sad' x0.45 + 'surprised' x0.55 (composed)") ||
              contains(report.emotions, "fear <- 'surprised' x0.55 + 'sad' x0.45 (composed)"))
      << report.summary();
  EXPECT_TRUE(contains(report.notes, "'relaxed' stands in for it")) << report.summary();
  std::vector<float> au(actionUnits().size(), 0.0f), emotions(kEmotionCount, 0.0f), morph(5, 0.0f);
  emotions[size_t(Emotion::Fear)] = 1.0f;
  ASSERT_TRUE(rig->apply(au, emotions, morph));
  EXPECT_FLOAT_EQ(morph[3], 0.55f);   // surprised's bind
  EXPECT_FLOAT_EQ(morph[2], 0.225f);  // sad's half-weight bind
}

TEST(VrmRig, MaterialColourAndTextureTransformBindsMoveTheMaterials) {
  Json doc = vrm1Document();
  Json& happy = doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["happy"];
  happy["materialColorBinds"].push_back(Json::parse(R"({"material": 1, "type": "emissionColor", "targetValue": [0, 1, 0, 1]})"));
  happy["materialColorBinds"].push_back(Json::parse(R"({"material": 1, "type": "rimColor", "targetValue": [1, 1, 1, 1]})"));
  happy["materialColorBinds"].push_back(Json::parse(R"({"material": 1, "type": "shadeColor", "targetValue": [0, 0, 1, 1]})"));
  happy["materialColorBinds"].push_back(Json::parse(R"({"material": 0, "type": "outlineColor", "targetValue": [1, 0, 0, 1]})"));
  happy["materialColorBinds"].push_back(Json::parse(R"({"material": 0, "type": "matcapColor", "targetValue": [1, 1, 1, 1]})"));
  happy["textureTransformBinds"] = Json::parse(R"([{"material": 1, "scale": [0.5, 0.5], "offset": [0.5, 0]}])");
  auto set = sharedSet(doc);
  ASSERT_TRUE(set);
  std::vector<float> weights(set->expressions.size(), 0.0f);
  weights[expressionIndex(*set, "happy")] = 0.5f;
  std::vector<VrmMaterialState> rest(2), materials(2);
  rest[0].color = {0.2f, 0.2f, 0.2f, 1.0f};
  std::vector<float> effective(weights.size());
  ASSERT_TRUE(set->effectiveWeights(weights, effective));
  ASSERT_TRUE(set->applyMaterials(effective, rest, materials));
  EXPECT_FLOAT_EQ(materials[0].color[0], 0.6f);  // halfway from 0.2 to 1
  EXPECT_FLOAT_EQ(materials[0].color[1], 0.1f);
  EXPECT_FLOAT_EQ(materials[1].emission[1], 0.5f);
  EXPECT_FLOAT_EQ(materials[1].uvScale[0], 0.75f);
  EXPECT_FLOAT_EQ(materials[1].uvOffset[0], 0.25f);
  // MToon's colours move the same way (drawn by toon materials), the matcap's too.
  EXPECT_FLOAT_EQ(materials[1].rim[0], 0.5f);
  EXPECT_FLOAT_EQ(materials[1].shade[2], 0.5f);
  EXPECT_FLOAT_EQ(materials[0].outline[0], 0.5f);
  EXPECT_FLOAT_EQ(materials[0].matcap[1], 0.5f);
  auto rig = buildVrmRigMapping(set, morphNames(*set));
  ASSERT_TRUE(rig);
  EXPECT_FALSE(contains(rig->report().notes, "matcap colour")) << rig->report().summary();
  std::vector<VrmMaterialState> wrong(1);
  EXPECT_FALSE(set->applyMaterials(effective, rest, wrong));
  EXPECT_FALSE(set->applyMaterials(effective, wrong, wrong));
  effective[0] = std::nanf("");
  EXPECT_FALSE(set->applyMaterials(effective, rest, materials));
}

TEST(VrmRig, Vrm0MainTexStIsATextureTransform) {
  Json doc = vrm0Document();
  doc["extensions"]["VRM"]["blendShapeMaster"]["blendShapeGroups"][0]["materialValues"] =
      Json::parse(R"([{"materialName": "skin", "propertyName": "_MainTex_ST", "targetValue": [1, 1, 0.25, 0]}])");
  auto set = importers::importVrmExpressions(doc, "old.vrm");
  ASSERT_TRUE(set) << set.error().message;
  ASSERT_EQ(set->textureTransformBinds.size(), 1u);
  EXPECT_EQ(set->textureTransformBinds[0].material, 0u);
  EXPECT_FLOAT_EQ(set->textureTransformBinds[0].offset[0], 0.25f);
  EXPECT_EQ(set->expressions[0].textureTransformBindCount, 1u);
}

// A material bind that cannot be applied is left out with one warning naming
// the file and the bind; the avatar (its other binds) still loads.
std::string onlyWarningOf(const Json& document, size_t colourBinds, size_t textureBinds) {
  auto set = importers::importVrmExpressions(document, "bad.vrm");
  EXPECT_TRUE(set) << set.error().message;
  if (!set) return {};
  EXPECT_EQ(set->materialColorBinds.size(), colourBinds);
  EXPECT_EQ(set->textureTransformBinds.size(), textureBinds);
  EXPECT_EQ(set->warnings.size(), 1u);
  return set->warnings.empty() ? std::string() : set->warnings.front();
}

TEST(VrmRigValidity, BadMaterialBindsAreSkippedWithOneWarning) {
  Json doc = vrm1Document();
  const size_t colours = importers::importVrmExpressions(doc, "bad.vrm")->materialColorBinds.size();
  const size_t textures = importers::importVrmExpressions(doc, "bad.vrm")->textureTransformBinds.size();
  Json& bind = doc["extensions"]["VRMC_vrm"]["expressions"]["preset"]["happy"]["materialColorBinds"][0];
  bind["type"] = "glow";
  EXPECT_EQ(onlyWarningOf(doc, colours - 1, textures),
            "bad.vrm: /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/0/type: must be color, "
            "emissionColor, shadeColor, matcapColor, rimColor or outlineColor, got \"glow\"; bind ignored");
  bind["type"] = "color";
  bind["material"] = 5;
  EXPECT_EQ(onlyWarningOf(doc, colours - 1, textures),
            "bad.vrm: /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/0/material: 5 is out of "
            "range (2 materials); bind ignored");
  bind["material"] = 0;
  bind["targetValue"] = Json::array({1, 0});
  EXPECT_NE(onlyWarningOf(doc, colours - 1, textures).find("materialColorBinds/0/targetValue: must be an array of 4 numbers"),
            std::string::npos);
  // JSON has no NaN: serialisers write a NaN colour as null.
  bind["targetValue"] = Json::parse("[1, null, 0, 1]");
  EXPECT_EQ(onlyWarningOf(doc, colours - 1, textures),
            "bad.vrm: /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/0/targetValue/1: must be a "
            "finite number, got null; bind ignored");
  // A document built in memory (or by a lenient parser) may carry a real NaN.
  bind["targetValue"] = Json::array({1.0, std::nan(""), 0.0, 1.0});
  EXPECT_NE(onlyWarningOf(doc, colours - 1, textures).find("materialColorBinds/0/targetValue/1: must be a finite number"),
            std::string::npos);
  // A finite double past the float range would become an infinite colour.
  bind["targetValue"] = Json::parse("[1, 1e39, 0, 1]");
  EXPECT_EQ(onlyWarningOf(doc, colours - 1, textures),
            "bad.vrm: /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/0/targetValue/1: must be a "
            "finite number, got 1e+39; bind ignored");
  doc = vrm0Document();
  doc["extensions"]["VRM"]["blendShapeMaster"]["blendShapeGroups"][4]["materialValues"][0]["materialName"] = "iris";
  const std::string warning = onlyWarningOf(doc, 0, 0);
  EXPECT_NE(warning.find("bad.vrm: /extensions/VRM/blendShapeMaster/blendShapeGroups/4/materialValues/0/materialName: "
                         "no material is named 'iris'; bind ignored"),
            std::string::npos)
      << warning;
}

// A material whose name is not a string is not the one a VRM 0.x value names.
TEST(VrmRigValidity, Vrm0MaterialNamesThatAreNotStringsAreSkipped) {
  Json doc = vrm0Document();
  doc["materials"][0]["name"] = 5;
  auto set = importers::importVrmExpressions(doc, "old.vrm");
  ASSERT_TRUE(set) << set.error().message;
  ASSERT_EQ(set->materialColorBinds.size(), 1u);
  EXPECT_EQ(set->materialColorBinds[0].material, 1u);  // "eye"
  EXPECT_TRUE(set->warnings.empty());
}

TEST(VrmRigValidity, StageAndTargetCountsMustAgree) {
  auto set = sharedSet(vrm1Document());
  ASSERT_TRUE(set);
  auto rig = buildVrmRigMapping(set, std::vector<std::string>{"a", "b"});
  ASSERT_FALSE(rig);
  EXPECT_NE(rig.error().message.find("address 5 morph targets, the model has 2"), std::string::npos);
  EXPECT_FALSE(buildVrmRigMapping(nullptr, {}));
}

TEST(VrmRig, SharedVrm0And1AvatarsBuildRigsOverTheirShapeKey) {
  FACIAL_REQUIRE_SHARED();
  for (const char* file : {"modifier_shapekey_vrm0.vrm", "modifier_shapekey_vrm1.vrm"}) {
    auto loaded = vrm_test::sharedVrmRig(file);
    ASSERT_TRUE(loaded);
    const RigMapping* rig = &loaded->rig;
    EXPECT_EQ(rig->scheme(), RigScheme::Expressions) << file;
    const RigMappingReport& report = rig->report();
    // The files bind the shape key only to the open vowel (0.x 'a', 1.0 'aa'): a viseme, no emotion moves the mesh.
    EXPECT_EQ(report.visemes.size(), 5u) << file << "\n" << report.summary();
    EXPECT_TRUE(contains(report.notes, "expressions that bind nothing")) << report.summary();
    EXPECT_TRUE(contains(report.emotions, std::string("happy <- '") + (loaded->expressions->specVersion == 0 ? "joy'" : "happy'")))
        << report.summary();
  }
  auto plain = importers::findVrmExpressions(testing_support::sharedDir() / "assets" / "facecap.glb");
  ASSERT_TRUE(plain) << plain.error().message;
  EXPECT_FALSE(plain->has_value());
}

}  // namespace
}  // namespace facial
