// The embedding API: facial::Character (C++) and its C wrapper over a graph
// file and a list of target names, as an engine without our loader uses them.
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/c_api.h"
#include "facial/character.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/rig/action_unit_rig.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "tests/common/test_support.h"

namespace {

std::filesystem::path data() { return testing_support::sourceDir() / "data"; }

const std::vector<std::string> kArkitFace = {"eyeBlinkLeft", "eyeBlinkRight", "mouthSmileLeft", "mouthSmileRight",
                                             "browInnerUp",  "jawOpen",        "eyeLookInLeft",  "eyeLookOutLeft",
                                             "eyeLookUpLeft", "eyeLookDownLeft", "eyeLookInRight", "eyeLookOutRight",
                                             "eyeLookUpRight", "eyeLookDownRight", "mouthFrownLeft", "mouthFrownRight"};

size_t indexOf(const std::string& name) {
  for (size_t i = 0; i < kArkitFace.size(); ++i)
    if (kArkitFace[i] == name) return i;
  return SIZE_MAX;
}

facial::Character tourCharacter(bool idleLife) {
  auto character = facial::Character::create(data() / "graphs" / "tour.json", kArkitFace,
                                             {.expressions = data() / "expressions.json", .seed = 3, .idleLife = idleLife});
  EXPECT_TRUE(character) << character.error().message;
  return std::move(*character);
}

}  // namespace

TEST(Character, TriggeredEmotionReachesTheTargets) {
  facial::Character character = tourCharacter(false);
  EXPECT_EQ(character.rigScheme(), "ARKit 52 blend shapes");
  EXPECT_EQ(character.gazeOutputs(), "ARKit eyeLook*");
  ASSERT_TRUE(character.setBool("autoplay", false));
  ASSERT_TRUE(character.trigger("happy"));
  for (int frame = 0; frame < 120; ++frame) ASSERT_TRUE(character.update(1.0f / 60.0f));
  ASSERT_EQ(character.weightCount(), kArkitFace.size());
  EXPECT_GT(character.weights()[indexOf("mouthSmileLeft")], 0.3f);
  EXPECT_GT(character.weights()[indexOf("mouthSmileRight")], 0.3f);
  EXPECT_LT(character.weights()[indexOf("mouthFrownLeft")], 0.05f);
}

TEST(Character, LookAtTurnsTheEyesAndTheirShapes) {
  facial::Character character = tourCharacter(false);
  ASSERT_TRUE(character.lookAt(1.0f, 0.0f, 1.0f));  // 45 degrees to the face's left: both eyes at their limit
  ASSERT_TRUE(character.update(0.0f));
  EXPECT_GT(character.weights()[indexOf("eyeLookOutLeft")], 0.99f);
  EXPECT_GT(character.weights()[indexOf("eyeLookInRight")], 0.99f);
  EXPECT_EQ(character.weights()[indexOf("eyeLookInLeft")], 0.0f);
  const auto eye = character.eyeRotation(facial::Eye::Left);  // {x, y, z, w}: a turn about +Y
  EXPECT_GT(eye[1], 0.2f);
  EXPECT_NEAR(eye[0], 0.0f, 1e-6f);
  character.lookAhead();
  ASSERT_TRUE(character.update(0.0f));
  EXPECT_EQ(character.weights()[indexOf("eyeLookOutLeft")], 0.0f);
}

TEST(Character, IdleLifeTurnsTheHead) {
  facial::Character character = tourCharacter(true);
  for (int frame = 0; frame < 90; ++frame) ASSERT_TRUE(character.update(1.0f / 60.0f));
  const auto head = character.headRotation();
  EXPECT_LT(head[3], 1.0f);
  EXPECT_GT(character.breathLift(), 0.0f);
}

// What a program that loads faces itself passes instead of files: the tour
// graph with the presets and the ARKit rig as an action-unit graph sees it.
struct LoadedTour {
  facial::SharedGraphDefinition graph;
  std::optional<facial::RigMapping> rig;
};

LoadedTour loadTour() {
  LoadedTour tour;
  auto presets = facial::ExpressionLibrary::load(data() / "expressions.json");
  EXPECT_TRUE(presets) << presets.error().message;
  if (!presets) return tour;
  auto graph = facial::loadGraph(data() / "graphs" / "tour.json", {.presets = facial::presetLookup(*presets)});
  EXPECT_TRUE(graph) << graph.error().message;
  auto rig = facial::buildRigMapping(kArkitFace);
  EXPECT_TRUE(rig) << rig.error().message;
  if (!graph || !rig) return tour;
  auto graphRig = facial::actionUnitRig(*rig, *presets);
  EXPECT_TRUE(graphRig) << graphRig.error().message;
  if (graphRig) tour.rig.emplace(std::move(*graphRig));
  tour.graph = *graph;
  return tour;
}

TEST(Character, FromLoadedPartsPlaysAsFromFiles) {
  const LoadedTour tour = loadTour();
  ASSERT_TRUE(tour.graph && tour.rig);
  auto fromParts = facial::Character::create({.graph = tour.graph, .rig = &*tour.rig}, kArkitFace, {.seed = 3});
  ASSERT_TRUE(fromParts) << fromParts.error().message;
  facial::Character fromFiles = tourCharacter(true);
  EXPECT_EQ(fromParts->rigScheme(), fromFiles.rigScheme());
  for (facial::Character* c : {&*fromParts, &fromFiles}) {
    ASSERT_TRUE(c->setBool("autoplay", false));
    ASSERT_TRUE(c->trigger("sad"));
  }
  for (int frame = 0; frame < 90; ++frame) {
    ASSERT_TRUE(fromParts->update(1.0f / 60.0f));
    ASSERT_TRUE(fromFiles.update(1.0f / 60.0f));
  }
  for (size_t t = 0; t < kArkitFace.size(); ++t) EXPECT_EQ(fromParts->weights()[t], fromFiles.weights()[t]) << kArkitFace[t];
  EXPECT_EQ(fromParts->headRotation(), fromFiles.headRotation());
  EXPECT_TRUE(fromParts->expressionWeights().empty()) << "an ARKit rig has no VRM expressions";
}

TEST(Character, LastTriggerWinsAfterAReset) {
  facial::Character character = tourCharacter(false);
  ASSERT_TRUE(character.setBool("autoplay", false));
  ASSERT_TRUE(character.trigger("sad"));
  ASSERT_TRUE(character.resetTrigger("sad"));
  ASSERT_TRUE(character.trigger("happy"));
  for (int frame = 0; frame < 120; ++frame) ASSERT_TRUE(character.update(1.0f / 60.0f));
  ASSERT_TRUE(character.currentState("emotions"));
  EXPECT_EQ(*character.currentState("emotions"), "happy");
  EXPECT_FALSE(character.currentState("nope").has_value());
  EXPECT_FALSE(character.resetTrigger("autoplay")) << "a bool is no trigger";
}

TEST(Character, MachineStatusTellsBlendingFromSettled) {
  facial::Character character = tourCharacter(false);
  ASSERT_TRUE(character.setBool("autoplay", false));
  for (int frame = 0; frame < 30; ++frame) ASSERT_TRUE(character.update(1.0f / 60.0f));  // settled in neutral
  ASSERT_TRUE(character.trigger("surprise"));
  ASSERT_TRUE(character.update(1.0f / 60.0f));
  auto blending = character.machineStatus("emotions");
  ASSERT_TRUE(blending);
  EXPECT_EQ(blending->state, "surprise") << "the destination while blending";
  EXPECT_TRUE(blending->blending);
  for (int frame = 0; frame < 180; ++frame) ASSERT_TRUE(character.update(1.0f / 60.0f));
  auto settled = character.machineStatus("emotions");
  ASSERT_TRUE(settled);
  EXPECT_EQ(settled->state, "surprise");
  EXPECT_FALSE(settled->blending);
  EXPECT_NEAR(settled->secondsInState, blending->secondsInState + 3.0f, 1e-3f);
  EXPECT_FALSE(character.machineStatus("nope").has_value());
}

TEST(Character, AnOverridePoseTakesOverByItsAmountUnderTheGaze) {
  facial::Character plain = tourCharacter(false);
  facial::Character posed = tourCharacter(false);
  const std::vector<float> half(kArkitFace.size(), 0.5f);
  ASSERT_TRUE(posed.overridePose(half, {}, 0.25f));
  for (int frame = 0; frame < 30; ++frame) {
    ASSERT_TRUE(plain.update(1.0f / 60.0f));
    ASSERT_TRUE(posed.update(1.0f / 60.0f));
  }
  for (size_t t = 0; t < kArkitFace.size(); ++t)
    EXPECT_FLOAT_EQ(posed.weights()[t], plain.weights()[t] + 0.25f * (0.5f - plain.weights()[t])) << kArkitFace[t];
  // All of it, and the gaze still added on top.
  ASSERT_TRUE(posed.overridePose(half, {}, 1.0f));
  ASSERT_TRUE(posed.lookAt(1.0f, 0.0f, 1.0f));
  ASSERT_TRUE(posed.update(1.0f / 60.0f));
  EXPECT_EQ(posed.weights()[indexOf("jawOpen")], 0.5f);
  EXPECT_EQ(posed.weights()[indexOf("eyeLookOutLeft")], 1.0f);
  // Nothing changes on a bad call.
  EXPECT_FALSE(posed.overridePose(std::vector<float>(3, 0.5f), {}, 1.0f));
  EXPECT_FALSE(posed.overridePose(half, {}, 1.5f));
  EXPECT_FALSE(posed.overridePose(half, std::vector<float>(2, 0.0f), 1.0f));
  ASSERT_TRUE(posed.update(1.0f / 60.0f));
  EXPECT_EQ(posed.weights()[indexOf("jawOpen")], 0.5f);
}

TEST(Character, TheEyesAimFromTheirGivenCentres) {
  // The target straight ahead of a left eye placed 0.5 to the left: that eye looks ahead, the right one turns in.
  auto character = facial::Character::create(data() / "graphs" / "tour.json", kArkitFace,
                                             {.expressions = data() / "expressions.json", .idleLife = false,
                                              .leftEye = {0.5f, 0.0f, 0.0f}, .rightEye = {-0.5f, 0.0f, 0.0f}});
  ASSERT_TRUE(character) << character.error().message;
  ASSERT_TRUE(character->lookAt(0.5f, 0.0f, 1.0f));
  ASSERT_TRUE(character->update(0.0f));
  EXPECT_EQ(character->weights()[indexOf("eyeLookOutLeft")], 0.0f);
  EXPECT_EQ(character->weights()[indexOf("eyeLookInLeft")], 0.0f);
  EXPECT_GT(character->weights()[indexOf("eyeLookInRight")], 0.5f);
}

TEST(CharacterValidity, UnknownParameterListsTheGraphs) {
  facial::Character character = tourCharacter(false);
  auto r = character.trigger("ecstatic");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("no trigger parameter 'ecstatic'"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("happy (trigger)"), std::string::npos) << r.error().message;
  EXPECT_FALSE(character.setFloat("happy", 1.0f)) << "a trigger is no float";
  EXPECT_FALSE(character.update(-1.0f));
  EXPECT_FALSE(character.lookAt(0.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f));
}

TEST(CharacterValidity, BadGraphOrNamesAreOneLine) {
  const std::vector<std::string> names = {"mystery", "enigma"};
  auto noRig = facial::Character::create(data() / "graphs" / "tour.json", names, {.expressions = data() / "expressions.json"});
  ASSERT_FALSE(noRig);
  EXPECT_EQ(noRig.error().message.find('\n'), std::string::npos) << noRig.error().message;
  auto missing = facial::Character::create("/nonexistent/graph.json", kArkitFace);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/graph.json"), std::string::npos) << missing.error().message;
  const std::vector<std::string> twice = {"jawOpen", "jawOpen"};
  auto duplicate = facial::Character::create(data() / "graphs" / "tour.json", twice);
  ASSERT_FALSE(duplicate);
  EXPECT_NE(duplicate.error().message.find("'jawOpen' is given twice"), std::string::npos) << duplicate.error().message;
}

TEST(CharacterValidity, PartsMustFitTheTargetNames) {
  const LoadedTour tour = loadTour();
  ASSERT_TRUE(tour.graph && tour.rig);
  const std::vector<float> threeRest(3, 0.0f);
  auto wrongRest = facial::Character::create({.graph = tour.graph, .rig = &*tour.rig, .restWeights = threeRest}, kArkitFace);
  ASSERT_FALSE(wrongRest);
  EXPECT_EQ(wrongRest.error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_NE(wrongRest.error().message.find("3 rest weights"), std::string::npos) << wrongRest.error().message;
  auto noGraph = facial::Character::create(facial::CharacterParts{}, kArkitFace);
  ASSERT_FALSE(noGraph);
  EXPECT_EQ(noGraph.error().kind, eng::ErrorKind::InvalidArgument);
  // An action-unit graph needs the rig.
  EXPECT_FALSE(facial::Character::create({.graph = tour.graph}, kArkitFace));
}

TEST(CApi, DrivesACharacterLikeTheCppApi) {
  std::vector<const char*> names;
  for (const std::string& n : kArkitFace) names.push_back(n.c_str());
  const std::string graph = (data() / "graphs" / "tour.json").string(), presets = (data() / "expressions.json").string();
  facial_character* c = nullptr;
  ASSERT_EQ(facial_character_create(graph.c_str(), presets.c_str(), names.data(), uint32_t(names.size()), 3, &c), FACIAL_OK)
      << facial_last_error_message();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(facial_character_set_bool(c, "autoplay", 0), FACIAL_OK);
  EXPECT_EQ(facial_character_trigger(c, "happy"), FACIAL_OK);
  for (int frame = 0; frame < 120; ++frame) ASSERT_EQ(facial_character_update(c, 1.0f / 60.0f), FACIAL_OK);
  ASSERT_EQ(facial_character_weight_count(c), kArkitFace.size());
  EXPECT_GT(facial_character_weights(c)[indexOf("mouthSmileLeft")], 0.3f);
  float q[4] = {0, 0, 0, 0};
  EXPECT_EQ(facial_character_head_rotation(c, q), FACIAL_OK);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-5f);
  EXPECT_EQ(facial_character_eye_rotation(c, FACIAL_EYE_RIGHT, q), FACIAL_OK);
  facial_character_destroy(c);
}

TEST(CApiValidity, ErrorsAreCodesWithAMessage) {
  facial_character* c = reinterpret_cast<facial_character*>(1);
  const char* names[] = {"jawOpen"};
  EXPECT_EQ(facial_character_create("/nonexistent/graph.json", nullptr, names, 1, 0, &c), FACIAL_ERROR_LOAD);
  EXPECT_EQ(c, nullptr) << "*out is cleared on failure";
  EXPECT_NE(std::string(facial_last_error_message()).find("/nonexistent/graph.json"), std::string::npos);
  EXPECT_EQ(facial_character_create(nullptr, nullptr, names, 1, 0, &c), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_create("g.json", nullptr, nullptr, 1, 0, &c), FACIAL_ERROR_INVALID_ARGUMENT);
  const char* holes[] = {"jawOpen", nullptr};
  EXPECT_EQ(facial_character_create("g.json", nullptr, holes, 2, 0, &c), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(facial_last_error_message()).find("target_names[1] is NULL"), std::string::npos);
  EXPECT_EQ(facial_character_create("g.json", nullptr, names, 1, 0, nullptr), FACIAL_ERROR_INVALID_ARGUMENT);

  EXPECT_EQ(facial_character_update(nullptr, 0.1f), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_weights(nullptr), nullptr);
  EXPECT_EQ(facial_character_weight_count(nullptr), 0u);
  facial_character_destroy(nullptr);

  std::vector<const char*> arkit;
  for (const std::string& n : kArkitFace) arkit.push_back(n.c_str());
  const std::string graph = (data() / "graphs" / "tour.json").string(), presets = (data() / "expressions.json").string();
  ASSERT_EQ(facial_character_create(graph.c_str(), presets.c_str(), arkit.data(), uint32_t(arkit.size()), 0, &c), FACIAL_OK);
  EXPECT_EQ(facial_character_trigger(c, "ecstatic"), FACIAL_ERROR_UNKNOWN_PARAMETER);
  EXPECT_NE(std::string(facial_last_error_message()).find("'ecstatic'"), std::string::npos);
  EXPECT_EQ(facial_character_set_float(c, "talk", std::numeric_limits<float>::infinity()), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_update(c, -0.5f), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_eye_rotation(c, facial_eye(7), nullptr), FACIAL_ERROR_INVALID_ARGUMENT);
  float q[4];
  EXPECT_EQ(facial_character_eye_rotation(c, facial_eye(7), q), FACIAL_ERROR_INVALID_ARGUMENT);
  facial_character_destroy(c);
}

TEST(CApiValidity, TheLastErrorKindTellsMissingFromBrokenFromMisuse) {
  facial_character* c = nullptr;
  const char* names[] = {"jawOpen"};
  EXPECT_EQ(facial_character_create("/nonexistent/graph.json", nullptr, names, 1, 0, &c), FACIAL_ERROR_LOAD);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_NOT_FOUND);

  const auto dir = testing_support::freshTempDir("c_api_error_kinds");
  const std::string broken = (dir / "broken.json").string();
  { std::ofstream(broken) << "{ \"nodes\": [ 1, "; }
  EXPECT_EQ(facial_character_create(broken.c_str(), nullptr, names, 1, 0, &c), FACIAL_ERROR_LOAD);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_MALFORMED) << facial_last_error_message();

  EXPECT_EQ(facial_character_update(nullptr, 0.1f), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_INVALID_ARGUMENT);

  std::vector<const char*> arkit;
  for (const std::string& n : kArkitFace) arkit.push_back(n.c_str());
  const std::string graph = (data() / "graphs" / "tour.json").string(), presets = (data() / "expressions.json").string();
  ASSERT_EQ(facial_character_create(graph.c_str(), presets.c_str(), arkit.data(), uint32_t(arkit.size()), 0, &c), FACIAL_OK);
  EXPECT_EQ(facial_character_trigger(c, "ecstatic"), FACIAL_ERROR_UNKNOWN_PARAMETER);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_NOT_FOUND);
  EXPECT_EQ(facial_character_update(c, -0.5f), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_INVALID_ARGUMENT);
  facial_character_destroy(c);

  const char* repeated[] = {"jawOpen", "jawOpen"};
  EXPECT_EQ(facial_character_create(graph.c_str(), presets.c_str(), repeated, 2, 0, &c), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_last_error_kind(), FACIAL_KIND_INVALID_ARGUMENT);
}
