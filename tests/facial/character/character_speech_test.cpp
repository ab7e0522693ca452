// Lip sync through the embedding API: facial::Character::speak over the tour
// graph (no speech node: the character layers speech itself) and over a graph
// with a speech node, the C API's timed phonemes / visemes, the refusal of a
// face that nothing can make speak, and no allocation per frame.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/c_api.h"
#include "facial/character.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/speech/viseme_track.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/test_support.h"

namespace {

std::filesystem::path dataDir() { return testing_support::sourceDir() / "data"; }

std::vector<std::string> arkitFace() {
  std::vector<std::string> names;
  for (std::string_view n : facial::arkitBlendShapeNames()) names.emplace_back(n);
  return names;
}

size_t targetIndex(const std::vector<std::string>& names, std::string_view name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  ADD_FAILURE() << "no target " << name;
  return 0;
}

// "p a p a": PP 0.1-0.2, aa 0.2-0.4, PP 0.4-0.5, aa 0.5-0.8.
std::shared_ptr<const facial::VisemeTrack> papa() {
  using facial::Viseme;
  const std::vector<facial::TimedViseme> cues = {
      {Viseme::PP, 0.1f, 0.2f}, {Viseme::aa, 0.2f, 0.4f}, {Viseme::PP, 0.4f, 0.5f}, {Viseme::aa, 0.5f, 0.8f}};
  auto built = facial::VisemeTrackBuilder{}.build(cues);
  EXPECT_TRUE(built) << built.error().message;
  return std::make_shared<const facial::VisemeTrack>(std::move(built->track));
}

facial::Character happyCharacter(const std::filesystem::path& graph, const std::vector<std::string>& names) {
  auto character = facial::Character::create(graph, names, {.expressions = dataDir() / "expressions.json", .idleLife = false,
                                                            .speaks = true});
  EXPECT_TRUE(character) << character.error().message;
  EXPECT_TRUE(character->setBool("autoplay", false));
  EXPECT_TRUE(character->trigger("happy"));
  for (int frame = 0; frame < 90; ++frame) EXPECT_TRUE(character->update(1.0f / 60.0f));
  return std::move(*character);
}

void checkHappyBilabial(facial::Character& character, const std::vector<std::string>& names) {
  const float smile = character.weights()[targetIndex(names, "mouthSmileLeft")];
  const float browUp = character.weights()[targetIndex(names, "cheekSquintLeft")];
  ASSERT_GT(smile, 0.3f);
  ASSERT_TRUE(character.speak(papa()));
  EXPECT_TRUE(character.speaking());
  ASSERT_TRUE(character.setSpeechTime(0.15f));
  ASSERT_TRUE(character.update(1.0f / 60.0f));
  EXPECT_GT(character.weights()[targetIndex(names, "mouthPressLeft")], 0.4f);   // the lips meet
  EXPECT_LT(character.weights()[targetIndex(names, "jawOpen")], 0.05f);
  EXPECT_GE(character.weights()[targetIndex(names, "mouthSmileLeft")], 0.5f * smile);  // still smiling
  EXPECT_NEAR(character.weights()[targetIndex(names, "cheekSquintLeft")], browUp, 1e-4f);
  ASSERT_TRUE(character.setSpeechTime(0.3f));
  ASSERT_TRUE(character.update(1.0f / 60.0f));
  EXPECT_GT(character.weights()[targetIndex(names, "jawOpen")], 0.5f);  // the open vowel
  character.stopSpeaking();
  EXPECT_FALSE(character.speaking());
  ASSERT_TRUE(character.update(1.0f / 60.0f));
  EXPECT_NEAR(character.weights()[targetIndex(names, "mouthSmileLeft")], smile, 1e-4f);
  EXPECT_EQ(character.weights()[targetIndex(names, "mouthPressLeft")], 0.0f);
}

}  // namespace

TEST(CharacterSpeech, HappyPresenterClosesTheLipsAndKeepsSmiling) {
  const std::vector<std::string> names = arkitFace();
  facial::Character character = happyCharacter(dataDir() / "graphs" / "tour.json", names);
  checkHappyBilabial(character, names);
}

TEST(CharacterSpeech, AGraphWithASpeechNodeLayersItItself) {
  const auto dir = testing_support::freshTempDir("character_speech_node");
  testing_support::writeFile(dir / "speaking.json", R"({"version": 1, "channels": "actionUnitsAndVisemes",
    "parameters": [{"name": "autoplay", "type": "bool"}, {"name": "happy", "type": "trigger"}],
    "root": {"type": "speech", "input": {"type": "stateMachine", "defaultState": "neutral", "states": [
      {"name": "neutral", "node": {"type": "pose", "preset": "neutral"}},
      {"name": "happy", "node": {"type": "pose", "preset": "happy"}}],
      "anyState": [{"to": "happy", "duration": 0.3, "conditions": [{"parameter": "happy"}]}]}}})");
  const std::vector<std::string> names = arkitFace();
  facial::Character character = happyCharacter(dir / "speaking.json", names);
  checkHappyBilabial(character, names);
}

TEST(CharacterSpeech, AFaceWithNothingToMoveTheMouthIsRefused) {
  const std::vector<std::string> eyes = {"eyeBlinkLeft", "eyeBlinkRight", "eyeWideLeft", "eyeWideRight",
                                         "eyeSquintLeft", "eyeSquintRight", "browInnerUp", "browDownLeft",
                                         "browDownRight", "browOuterUpLeft", "browOuterUpRight"};
  const auto graph = dataDir() / "graphs" / "tour.json";
  auto refused = facial::Character::create(graph, eyes, {.expressions = dataDir() / "expressions.json", .speaks = true});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, eng::ErrorKind::Unsupported);
  EXPECT_NE(refused.error().message.find("cannot speak"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("none of its 11 targets"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("ARKit jawOpen/mouth*"), std::string::npos) << refused.error().message;
  auto silent = facial::Character::create(graph, eyes, {.expressions = dataDir() / "expressions.json"});
  ASSERT_TRUE(silent) << silent.error().message;
  auto spoken = silent->speak(papa());
  ASSERT_FALSE(spoken);
  EXPECT_NE(spoken.error().message.find("cannot speak"), std::string::npos);
  EXPECT_FALSE(silent->speaking());
}

TEST(CharacterSpeechValidity, BadTracksAndTimesChangeNothing) {
  const std::vector<std::string> names = arkitFace();
  auto character = facial::Character::create(dataDir() / "graphs" / "tour.json", names,
                                             {.expressions = dataDir() / "expressions.json", .idleLife = false});
  ASSERT_TRUE(character) << character.error().message;
  EXPECT_FALSE(character->speak(nullptr));
  EXPECT_FALSE(character->speak(std::make_shared<const facial::VisemeTrack>()));
  EXPECT_FALSE(character->speaking());
  ASSERT_TRUE(character->speak(papa()));
  EXPECT_FALSE(character->setSpeechTime(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_TRUE(character->speaking());
}

TEST(CharacterSpeech, NoAllocationPerFrameWhileSpeaking) {
  const std::vector<std::string> names = arkitFace();
  facial::Character character = happyCharacter(dataDir() / "graphs" / "tour.json", names);
  ASSERT_TRUE(character.speak(papa()));
  ASSERT_TRUE(character.update(1.0f / 60.0f));
  const uint64_t before = testing_support::allocationCount();
  bool ok = true;
  for (int frame = 0; frame < 120; ++frame) {
    ok &= bool(character.setSpeechTime(frame / 120.0f));
    ok &= bool(character.update(1.0f / 120.0f));
  }
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
  EXPECT_TRUE(ok);
}

TEST(CharacterSpeechCApi, TimedPhonemesAndVisemesDriveTheMouth) {
  const std::vector<std::string> names = arkitFace();
  std::vector<const char*> pointers;
  for (const std::string& n : names) pointers.push_back(n.c_str());
  const std::string graph = (dataDir() / "graphs" / "tour.json").string();
  const std::string expressions = (dataDir() / "expressions.json").string();
  facial_character* c = nullptr;
  ASSERT_EQ(facial_character_create(graph.c_str(), expressions.c_str(), pointers.data(), uint32_t(pointers.size()), 1, &c),
            FACIAL_OK)
      << facial_last_error_message();
  ASSERT_EQ(facial_character_set_bool(c, "autoplay", 0), FACIAL_OK);
  const facial_timed_phoneme phonemes[] = {{"p", 0.1f, 0.2f}, {"a", 0.2f, 0.4f}, {"m", 0.4f, 0.5f}};
  ASSERT_EQ(facial_character_speak_phonemes(c, phonemes, 3), FACIAL_OK) << facial_last_error_message();
  ASSERT_EQ(facial_character_set_speech_time(c, 0.15f), FACIAL_OK);
  ASSERT_EQ(facial_character_update(c, 1.0f / 60.0f), FACIAL_OK);
  EXPECT_GT(facial_character_weights(c)[targetIndex(names, "mouthPressLeft")], 0.4f);
  ASSERT_EQ(facial_character_set_speech_time(c, 0.3f), FACIAL_OK);
  ASSERT_EQ(facial_character_update(c, 1.0f / 60.0f), FACIAL_OK);
  EXPECT_GT(facial_character_weights(c)[targetIndex(names, "jawOpen")], 0.5f);

  const facial_timed_viseme visemes[] = {{"viseme_U", 0.0f, 0.3f}, {"PP", 0.3f, 0.4f}};
  ASSERT_EQ(facial_character_speak_visemes(c, visemes, 2), FACIAL_OK) << facial_last_error_message();
  ASSERT_EQ(facial_character_set_speech_time(c, 0.15f), FACIAL_OK);
  ASSERT_EQ(facial_character_update(c, 1.0f / 60.0f), FACIAL_OK);
  EXPECT_GT(facial_character_weights(c)[targetIndex(names, "mouthPucker")], 0.5f);

  const facial_timed_viseme unknown[] = {{"oo", 0.0f, 0.3f}};
  EXPECT_EQ(facial_character_speak_visemes(c, unknown, 1), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(facial_last_error_message()).find("cue 0: viseme is not one of sil, PP"), std::string::npos)
      << facial_last_error_message();
  const facial_timed_phoneme overlapping[] = {{"p", 0.1f, 0.3f}, {"a", 0.2f, 0.4f}};
  EXPECT_EQ(facial_character_speak_phonemes(c, overlapping, 2), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_speak_phonemes(c, nullptr, 2), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_set_speech_time(c, std::numeric_limits<float>::infinity()), FACIAL_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(facial_character_set_speech_time(nullptr, 0.0f), FACIAL_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(facial_character_stop_speaking(c), FACIAL_OK);
  ASSERT_EQ(facial_character_update(c, 1.0f / 60.0f), FACIAL_OK);
  EXPECT_EQ(facial_character_weights(c)[targetIndex(names, "mouthPucker")], 0.0f);
  facial_character_destroy(c);
}
