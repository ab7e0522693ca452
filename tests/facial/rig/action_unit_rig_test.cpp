// facial::actionUnitRig: whole-expression (emotion) bindings re-expressed over
// action units by least squares through the basic presets.
#include "facial/runtime/rig/action_unit_rig.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "tests/common/test_support.h"

namespace {

class ActionUnitRig : public ::testing::Test {
 protected:
  void SetUp() override {
    auto library = facial::ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
    ASSERT_TRUE(library) << library.error().message;
    library_.emplace(std::move(*library));
  }
  // Target weights of `rig` for the AU vector of `preset` at `intensity` (no emotion channels).
  std::vector<float> fromActionUnits(const facial::RigMapping& rig, std::string_view preset, float intensity) {
    std::vector<float> au(facial::actionUnits().size()), weights(rig.targetCount(), 0.0f);
    EXPECT_TRUE(facial::ExpressionLibrary::evaluate(*library_->find(preset), intensity, au));
    auto applied = rig.apply(au, weights);
    EXPECT_TRUE(applied) << applied.error().message;
    return weights;
  }
  std::optional<facial::ExpressionLibrary> library_;
};

TEST_F(ActionUnitRig, EachBasicPresetDrivesOnlyItsOwnWholeExpressionTarget) {
  const std::vector<std::string> targets = {"smile", "frown", "scowl", "dread", "gasp", "sneer", "blink"};
  const char* emotions[] = {"happy", "sad", "anger", "fear", "surprise", "disgust"};
  auto rig = facial::parseRigMap(R"({"version": 1, "map": {
      "happy": [{"target": "smile", "weight": 1}], "sad": [{"target": "frown", "weight": 1}],
      "anger": [{"target": "scowl", "weight": 1}], "fear": [{"target": "dread", "weight": 1}],
      "surprise": [{"target": "gasp", "weight": 1}], "disgust": [{"target": "sneer", "weight": 0.5}],
      "AU45_Blink_L": [{"target": "blink", "weight": 1}]}})",
                                 "test map", targets);
  ASSERT_TRUE(rig) << rig.error().message;
  auto folded = facial::actionUnitRig(*rig, *library_);
  ASSERT_TRUE(folded) << folded.error().message;
  for (int e = 0; e < 6; ++e) {
    for (const float intensity : {1.0f, 0.4f}) {
      const std::vector<float> w = fromActionUnits(*folded, emotions[e], intensity);
      for (int t = 0; t < 6; ++t) {
        const float expected = t == e ? intensity * (t == 5 ? 0.5f : 1.0f) : 0.0f;
        EXPECT_NEAR(w[t], expected, 1e-4f) << emotions[e] << " at " << intensity << ", target " << targets[t];
      }
      EXPECT_EQ(w[6], 0.0f) << "no preset blinks";
    }
  }
  // A cosine-eased blend of two presets is the same blend of their targets.
  std::vector<float> happy(facial::actionUnits().size()), anger(happy.size()), mix(happy.size());
  ASSERT_TRUE(facial::ExpressionLibrary::evaluate(*library_->find("happy"), 1.0f, happy));
  ASSERT_TRUE(facial::ExpressionLibrary::evaluate(*library_->find("anger"), 1.0f, anger));
  for (size_t a = 0; a < mix.size(); ++a) mix[a] = 0.3f * happy[a] + 0.7f * anger[a];
  std::vector<float> w(targets.size(), 0.0f);
  ASSERT_TRUE(folded->apply(mix, w));
  EXPECT_NEAR(w[0], 0.3f, 1e-4f);
  EXPECT_NEAR(w[2], 0.7f, 1e-4f);
  // The AU rows are kept: blink still blinks.
  std::vector<float> blink(facial::actionUnits().size(), 0.0f);
  blink[*facial::actionUnitIndex("AU45_Blink_L")] = 1.0f;
  std::fill(w.begin(), w.end(), 0.0f);
  ASSERT_TRUE(folded->apply(blink, w));
  EXPECT_EQ(w[6], 1.0f);
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3] + w[4] + w[5], 0.0f, 1e-5f) << "blinking is no emotion";
}

TEST_F(ActionUnitRig, RigsWithoutEmotionBindingsAreKeptAsTheyAre) {
  const std::vector<std::string> targets = {"smileL", "browDown"};
  auto rig = facial::parseRigMap(R"({"version": 1, "map": {
      "AU12_LipCornerPuller_L": [{"target": "smileL", "weight": 1}], "AU4_BrowLowerer": [{"target": "browDown", "weight": 0.5}]}})",
                                 "au map", targets);
  ASSERT_TRUE(rig) << rig.error().message;
  auto folded = facial::actionUnitRig(*rig, *library_);
  ASSERT_TRUE(folded) << folded.error().message;
  EXPECT_EQ(fromActionUnits(*folded, "happy", 0.8f), fromActionUnits(*rig, "happy", 0.8f));
  EXPECT_EQ(folded->report().notes, rig->report().notes);
}

TEST_F(ActionUnitRig, MissingBasicPresetIsNamed) {
  auto library = facial::ExpressionLibrary::parse(
      R"({"version": 1, "expressions": {"happy": {"actionUnits": {"AU12_LipCornerPuller_L": 1}}}})", "tiny.json");
  ASSERT_TRUE(library) << library.error().message;
  const std::vector<std::string> targets = {"Happy", "Sad"};
  auto rig = facial::buildRigMapping(targets);
  ASSERT_TRUE(rig) << rig.error().message;
  auto folded = facial::actionUnitRig(*rig, *library);
  ASSERT_FALSE(folded);
  EXPECT_NE(folded.error().message.find("no basic 'sad'"), std::string::npos) << folded.error().message;
}

}  // namespace
