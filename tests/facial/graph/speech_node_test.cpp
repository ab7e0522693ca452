// The speech node: JSON reading, the mouth-ownership rule over an emotion
// (speech owns the opening shapes, the smile and frown are shared, the brows
// and cheeks stay), the viseme channels, an emotion change mid-sentence and
// no allocation per frame.
#include "facial/runtime/graph/nodes/speech_node.h"

#include <gtest/gtest.h>

#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/speech/viseme_action_units.h"
#include "facial/runtime/speech/viseme_track.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;

namespace {

std::filesystem::path writeGraph(const std::string& name, const std::string& text) {
  const auto dir = testing_support::freshTempDir("speech_node_" + name);
  testing_support::writeFile(dir / (name + ".json"), text);
  return dir / (name + ".json");
}

// A happy face (smile, cheeks, lips parted) that a trigger turns sad (brows, lowered corners).
std::string speakingGraph(const std::string& channels = "actionUnitsAndVisemes", const std::string& extra = "") {
  return R"({"version": 1, "channels": ")" + channels + R"(",
    "parameters": [{"name": "sad", "type": "trigger"}, {"name": "talk", "type": "float", "default": 1}],
    "root": {"type": "speech", "name": "mouth", "amount": "talk")" + extra + R"(, "input": {
      "type": "stateMachine", "name": "emotions", "defaultState": "happy", "states": [
        {"name": "happy", "node": {"type": "pose", "weights": {"AU12_LipCornerPuller_L": 1, "AU12_LipCornerPuller_R": 1,
                                                               "AU6_CheekRaiser": 0.8, "AU25_LipsPart": 0.6, "AU26_JawDrop": 0.3}}},
        {"name": "sad", "node": {"type": "pose", "weights": {"AU1_InnerBrowRaiser": 1, "AU4_BrowLowerer": 0.6,
                                                             "AU15_LipCornerDepressor": 0.8}}}],
      "anyState": [{"to": "sad", "duration": 0.2, "conditions": [{"parameter": "sad"}]}]}}})";
}

// "p a p a": PP 0.1-0.2, aa 0.2-0.4, PP 0.4-0.5, aa 0.5-0.8; rest around.
VisemeTrack papaTrack() {
  const std::vector<TimedViseme> cues = {
      {Viseme::PP, 0.1f, 0.2f}, {Viseme::aa, 0.2f, 0.4f}, {Viseme::PP, 0.4f, 0.5f}, {Viseme::aa, 0.5f, 0.8f}};
  auto built = VisemeTrackBuilder{}.build(cues);
  EXPECT_TRUE(built) << built.error().message;
  return std::move(built->track);
}

struct Speaker {
  Speaker() {
    auto graph = loadGraph(writeGraph("speaking", speakingGraph()));
    EXPECT_TRUE(graph) << graph.error().message;
    face.emplace(graph_test::instantiate(*graph));
    sad = *(*graph)->findParameter("sad");
  }
  float at(std::string_view channel) const {
    return face->weights()[*face->definition().channels().find(channel)];
  }
  void play(float time) {
    ASSERT_TRUE(face->setSpeech(&track, time));
    ASSERT_TRUE(face->update(1.0f / 60.0f));
  }
  VisemeTrack track = papaTrack();
  std::optional<GraphInstance> face;
  ParameterIndex sad = 0;
};

}  // namespace

TEST(SpeechNode, ReadsFromJsonOverActionUnitsAndVisemes) {
  auto graph = loadGraph(writeGraph("speaking", speakingGraph()));
  ASSERT_TRUE(graph) << graph.error().message;
  const auto node = (*graph)->findNode("mouth");
  ASSERT_TRUE(node);
  const SpeechNode* speech = (*graph)->nodeAs<SpeechNode>(*node);
  ASSERT_NE(speech, nullptr);
  EXPECT_EQ(speech->firstVisemeChannel, actionUnits().size());
  EXPECT_EQ((*graph)->channelCount(), actionUnits().size() + kVisemeCount);
  EXPECT_EQ((*graph)->channels()[speech->firstVisemeChannel + 1].name, "viseme_PP");
}

TEST(SpeechNodeValidity, NeedsVisemeChannelsAndKnownMembers) {
  auto actionUnitsOnly = loadGraph(writeGraph("au", speakingGraph("actionUnits")));
  ASSERT_FALSE(actionUnitsOnly);
  EXPECT_NE(actionUnitsOnly.error().message.find("needs the graph's channels to be \"actionUnitsAndVisemes\""),
            std::string::npos)
      << actionUnitsOnly.error().message;
  auto unknown = loadGraph(writeGraph("unknown", speakingGraph("actionUnitsAndVisemes", R"(, "volume": 2)")));
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("volume"), std::string::npos) << unknown.error().message;
  auto badSet = loadGraph(writeGraph("badset", speakingGraph("visemes")));
  ASSERT_FALSE(badSet);
  EXPECT_NE(badSet.error().message.find("actionUnitsAndVisemes"), std::string::npos) << badSet.error().message;
}

TEST(SpeechNode, SilentWithoutATrack) {
  Speaker s;
  ASSERT_TRUE(s.face->update(1.0f / 60.0f));
  EXPECT_FLOAT_EQ(s.at("AU25_LipsPart"), 0.6f);
  EXPECT_FLOAT_EQ(s.at("AU12_LipCornerPuller_L"), 1.0f);
  for (size_t v = 0; v < kVisemeCount; ++v) EXPECT_EQ(s.at(rigVisemeInputName(Viseme(v))), 0.0f);
}

TEST(SpeechNode, BilabialClosesAHappyMouthWhileTheSmileAndCheeksStay) {
  Speaker s;
  s.play(0.15f);  // inside the first p
  EXPECT_NEAR(s.at("viseme_PP"), 1.0f, 0.02f);
  EXPECT_LT(s.at("AU25_LipsPart"), 0.02f);  // the emotion's parted lips yield
  EXPECT_LT(s.at("AU26_JawDrop"), 0.02f);
  EXPECT_GE(s.at("AU12_LipCornerPuller_L"), 0.5f);  // the smile stays above half, eased for the closure
  EXPECT_LE(s.at("AU12_LipCornerPuller_L"), 0.6f);
  EXPECT_FLOAT_EQ(s.at("AU6_CheekRaiser"), 0.8f);
  s.play(0.3f);  // the open vowel
  EXPECT_GT(s.at("viseme_aa"), 0.9f);
  EXPECT_GE(s.at("AU12_LipCornerPuller_R"), 0.74f);  // 3/4 of the smile through open vowels
  s.play(2.0f);  // after the sentence: the emotion's own mouth again
  EXPECT_NEAR(s.at("AU25_LipsPart"), 0.6f, 1e-4f);
  EXPECT_NEAR(s.at("viseme_sil"), 1.0f, 1e-4f);
}

TEST(SpeechNode, AmountZeroLeavesTheInputAlone) {
  Speaker s;
  ASSERT_TRUE(s.face->setFloat(*s.face->definition().findParameter("talk"), 0.0f));
  s.play(0.15f);
  EXPECT_FLOAT_EQ(s.at("AU25_LipsPart"), 0.6f);
  EXPECT_EQ(s.at("viseme_PP"), 0.0f);
}

TEST(SpeechNode, EmotionChangesInTheMiddleOfASentence) {
  Speaker s;
  s.play(0.15f);
  ASSERT_TRUE(s.face->setTrigger(s.sad));
  for (float t = 0.15f; t < 0.45f; t += 1.0f / 60.0f) s.play(t);
  s.play(0.45f);  // the second p, now sad
  EXPECT_NEAR(s.at("viseme_PP"), 1.0f, 0.02f);
  EXPECT_NEAR(s.at("AU1_InnerBrowRaiser"), 1.0f, 1e-4f);  // brows untouched by speech
  EXPECT_NEAR(s.at("AU4_BrowLowerer"), 0.6f, 1e-4f);
  EXPECT_GE(s.at("AU15_LipCornerDepressor"), 0.8f * 0.7f - 1e-4f);  // the sad corners stay
  EXPECT_LT(s.at("AU12_LipCornerPuller_L"), 1e-4f);
}

TEST(SpeechNode, NoAllocationPerFrame) {
  Speaker s;
  s.play(0.0f);
  const uint64_t before = testing_support::allocationCount();
  for (int frame = 0; frame < 120; ++frame) {
    s.face->setSpeech(&s.track, frame / 120.0f);
    s.face->update(1.0f / 120.0f);
  }
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
}

TEST(MouthOwnership, TableSaysWhoOwnsEachMouthChannel) {
  std::vector<float> au(actionUnits().size(), 1.0f);
  yieldMouthToSpeech(au, 1.0f, 0.0f);
  auto at = [&](std::string_view channel) { return au[*actionUnitIndex(channel)]; };
  for (std::string_view owned : {"AU25_LipsPart", "AU26_JawDrop", "AU20_LipStretcher", "AU24_LipPressor", "AU23_LipTightener",
                                 "AU16_LowerLipDepressor"})
    EXPECT_EQ(at(owned), 0.0f) << owned;
  EXPECT_FLOAT_EQ(at("AU12_LipCornerPuller_L"), 0.75f);
  EXPECT_FLOAT_EQ(at("AU15_LipCornerDepressor"), 0.85f);
  for (std::string_view kept : {"AU1_InnerBrowRaiser", "AU4_BrowLowerer", "AU6_CheekRaiser", "AU5_UpperLidRaiser",
                                "AU45_Blink_L", "AU9_NoseWrinkler"})
    EXPECT_EQ(at(kept), 1.0f) << kept;
  std::vector<float> closing(actionUnits().size(), 1.0f);
  yieldMouthToSpeech(closing, 1.0f, 1.0f);
  EXPECT_FLOAT_EQ(closing[*actionUnitIndex("AU12_LipCornerPuller_R")], 0.55f);
  std::vector<float> silent(actionUnits().size(), 0.7f);
  yieldMouthToSpeech(silent, 0.0f, 1.0f);
  EXPECT_EQ(silent, std::vector<float>(actionUnits().size(), 0.7f));
  for (const MouthOwnership& row : mouthOwnershipTable()) {
    EXPECT_TRUE(actionUnitIndex(row.channel)) << row.channel;
    EXPECT_LE(row.keptOnClosure, row.kept) << row.channel;
  }
}
