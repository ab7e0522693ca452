// ExpressionLibrary: the project's presets (data/expressions.json) follow the
// cited FACS prototypes; evaluation scales and clamps; malformed files are
// refused with file + JSON path + problem.
#include "facial/runtime/rig/expression_library.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

const std::filesystem::path kPresetsFile = testing_support::sourceDir() / "data" / "expressions.json";

uint32_t channel(std::string_view name) {
  const std::optional<uint32_t> index = actionUnitIndex(name);
  EXPECT_TRUE(index.has_value()) << name;
  return index.value_or(0);
}

// Largest weight the preset gives any channel of FACS unit `number`.
float facsWeight(const ExpressionPreset& preset, int number) {
  float w = 0.0f;
  for (const ActionUnitWeight& au : preset.actionUnits)
    if (actionUnits()[au.channel].facsNumber == number) w = std::max(w, au.weight);
  return w;
}

// The trimmed cells of a Markdown table row "| a | b |", or none for another line.
std::vector<std::string> tableCells(const std::string& line) {
  std::vector<std::string> cells;
  if (line.size() < 2 || line.front() != '|' || line.back() != '|') return cells;
  std::istringstream row(line.substr(1, line.size() - 2));
  for (std::string cell; std::getline(row, cell, '|');) {
    const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? std::string() : cell.substr(first, last - first + 1));
  }
  return cells;
}

class ProjectPresets : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = ExpressionLibrary::load(kPresetsFile);
    ASSERT_TRUE(loaded) << loaded.error().message;
    library_ = std::move(*loaded);
  }
  ExpressionLibrary library_;
};

TEST_F(ProjectPresets, HasTheSixBasicEmotionsNeutralAndAtLeastFourCompounds) {
  for (std::string_view name : {"neutral", "happy", "sad", "surprise", "fear", "anger", "disgust"}) {
    const ExpressionPreset* preset = library_.find(name);
    ASSERT_NE(preset, nullptr) << name;
    EXPECT_FALSE(preset->isCompound()) << name;
    EXPECT_FALSE(library_.isCompound(name)) << name;
  }
  size_t compounds = 0;
  for (const ExpressionPreset& p : library_.presets()) compounds += p.isCompound() ? 1 : 0;
  EXPECT_GE(compounds, 4u);
  EXPECT_EQ(library_.names().front(), "neutral");  // file order
  EXPECT_EQ(library_.names().size(), library_.size());
  EXPECT_EQ(library_.find("elation"), nullptr);
  EXPECT_FALSE(library_.isCompound("elation"));
}

TEST_F(ProjectPresets, BasicEmotionsContainTheirEmfacsPrototypeUnits) {
  const std::map<std::string, std::vector<int>> prototypes = {
      {"happy", {6, 12}},
      {"sad", {1, 4, 15}},
      {"surprise", {1, 2, 5, 26}},
      // EMFACS fear 1+2+4+5+7+20+26, with 25 (7 at half: the tensed lower lid of fear's wide eye).
      {"fear", {1, 2, 4, 5, 7, 20, 25}},
      {"anger", {4, 5, 7, 23}},
      {"disgust", {9, 15, 16}},
  };
  for (const auto& [name, units] : prototypes) {
    const ExpressionPreset* preset = library_.find(name);
    ASSERT_NE(preset, nullptr) << name;
    for (int au : units) EXPECT_GE(facsWeight(*preset, au), 0.3f) << name << " lacks AU" << au;
    EXPECT_FLOAT_EQ(preset->emotions[*emotionIndex(name)], 1.0f) << name;
  }
  EXPECT_TRUE(library_.find("neutral")->actionUnits.empty());
  // Units that contradict an emotion stay off (a frown has no smile in it).
  EXPECT_EQ(facsWeight(*library_.find("sad"), 12), 0.0f);
  EXPECT_EQ(facsWeight(*library_.find("happy"), 15), 0.0f);
  EXPECT_EQ(facsWeight(*library_.find("anger"), 12), 0.0f);
}

TEST_F(ProjectPresets, CompoundsContainDuTaoMartinezUnitsAndBothComponents) {
  const std::map<std::string, std::vector<int>> prototypes = {
      {"happily_surprised", {1, 2, 12, 25}},
      {"happily_disgusted", {10, 12, 25}},
      {"sadly_angry", {4, 7, 15}},
      {"fearfully_surprised", {1, 2, 4, 5, 20, 25}},
      {"angrily_surprised", {4, 25, 26}},
      {"disgustedly_surprised", {1, 2, 5, 10}},
  };
  for (const auto& [name, units] : prototypes) {
    const ExpressionPreset* preset = library_.find(name);
    ASSERT_NE(preset, nullptr) << name;
    EXPECT_TRUE(preset->isCompound()) << name;
    ASSERT_EQ(preset->components.size(), 2u) << name;
    for (int au : units) EXPECT_GE(facsWeight(*preset, au), 0.3f) << name << " lacks AU" << au;
    for (Emotion e : preset->components) EXPECT_GT(preset->emotions[static_cast<size_t>(e)], 0.0f) << name;
  }
}

TEST_F(ProjectPresets, BilateralUnitsAreSetOnBothSides) {
  for (const ExpressionPreset& preset : library_.presets()) {
    for (auto [left, right] : {std::pair{"AU2_OuterBrowRaiser_L", "AU2_OuterBrowRaiser_R"},
                               std::pair{"AU12_LipCornerPuller_L", "AU12_LipCornerPuller_R"},
                               std::pair{"AU45_Blink_L", "AU45_Blink_R"}})
      EXPECT_EQ(preset.actionUnitWeight(channel(left)), preset.actionUnitWeight(channel(right))) << preset.name;
  }
}

// The preset tables in docs/expressions.md are what a user reads to know what
// a state does: each row ("| happily surprised | 1+2+12+25 [5, 26] | AU1 .8,
// AU2 L/R .8, ... |") must list the weights the file ships (three rows had
// kept older weights after the presets were tuned).
TEST_F(ProjectPresets, DocsTablesListTheWeightsTheFileShips) {
  std::ifstream doc(testing_support::sourceDir() / "docs" / "expressions.md");
  ASSERT_TRUE(doc) << "docs/expressions.md not found";
  std::set<std::string> documented;
  for (std::string line; std::getline(doc, line);) {
    // A preset row has three cells: name (lower case words), FACS, weights.
    const std::vector<std::string> cells = tableCells(line);
    if (cells.size() != 3 || cells[0].empty() ||
        cells[0].find_first_not_of("abcdefghijklmnopqrstuvwxyz ") != std::string::npos)
      continue;
    std::string name = cells[0];
    std::replace(name.begin(), name.end(), ' ', '_');
    const ExpressionPreset* preset = library_.find(name);
    if (!preset) continue;
    documented.insert(name);
    std::set<int> listed;
    // Entries "AU<n> <weight>" or "AU<n> L/R <weight>", comma separated.
    std::istringstream entries(cells[2]);
    for (std::string entry; std::getline(entries, entry, ',');) {
      std::istringstream words(entry);
      std::string unit, weight;
      words >> unit;
      for (std::string word; words >> word;) weight = word;
      if (unit.rfind("AU", 0) != 0 || weight.empty()) continue;
      const int number = std::stoi(unit.substr(2));
      listed.insert(number);
      EXPECT_NEAR(facsWeight(*preset, number), std::stof(weight), 1e-4f) << name << ": AU" << number << " in docs/expressions.md";
    }
    std::set<int> shipped;
    for (const ActionUnitWeight& au : preset->actionUnits) shipped.insert(actionUnits()[au.channel].facsNumber);
    EXPECT_EQ(listed, shipped) << name << ": docs/expressions.md lists other action units than data/expressions.json";
  }
  for (std::string_view name : library_.names()) EXPECT_TRUE(documented.count(std::string(name))) << name << " has no row in docs/expressions.md";
}

TEST_F(ProjectPresets, EvaluateScalesByIntensityAndClampsToUnitRange) {
  const ExpressionPreset& happy = *library_.find("happy");
  std::vector<float> weights(actionUnits().size(), 7.0f);  // stale garbage must be overwritten
  ASSERT_TRUE(ExpressionLibrary::evaluate(happy, 0.5f, weights));
  EXPECT_FLOAT_EQ(weights[channel("AU12_LipCornerPuller_L")], 0.5f);
  EXPECT_FLOAT_EQ(weights[channel("AU6_CheekRaiser")], 0.5f);
  EXPECT_FLOAT_EQ(weights[channel("AU25_LipsPart")], 0.3f);
  EXPECT_EQ(weights[channel("AU4_BrowLowerer")], 0.0f);

  ASSERT_TRUE(ExpressionLibrary::evaluate(happy, 3.0f, weights));
  EXPECT_FLOAT_EQ(weights[channel("AU12_LipCornerPuller_L")], 1.0f);
  EXPECT_FLOAT_EQ(weights[channel("AU6_CheekRaiser")], 1.0f);

  ASSERT_TRUE(ExpressionLibrary::evaluate(happy, -1.0f, weights));
  for (float w : weights) EXPECT_EQ(w, 0.0f);

  std::vector<float> emotions(kEmotionCount, 5.0f);
  ASSERT_TRUE(ExpressionLibrary::evaluateEmotions(*library_.find("happily_surprised"), 0.5f, emotions));
  EXPECT_FLOAT_EQ(emotions[static_cast<size_t>(Emotion::Happy)], 0.325f);
  EXPECT_FLOAT_EQ(emotions[static_cast<size_t>(Emotion::Surprise)], 0.325f);
  EXPECT_EQ(emotions[static_cast<size_t>(Emotion::Anger)], 0.0f);
}

TEST(ExpressionLibrary, EmotionsDefaultToOwnNameOrEqualComponentShares) {
  auto library = ExpressionLibrary::parse(R"({"version": 1, "expressions": {
      "sad": {"actionUnits": {"AU15_LipCornerDepressor": 1.0}},
      "wistful": {"components": ["happy", "sad"]},
      "custom": {}}})",
                                          "inline.json");
  ASSERT_TRUE(library) << library.error().message;
  EXPECT_FLOAT_EQ(library->find("sad")->emotions[static_cast<size_t>(Emotion::Sad)], 1.0f);
  const ExpressionPreset& wistful = *library->find("wistful");
  EXPECT_FLOAT_EQ(wistful.emotions[static_cast<size_t>(Emotion::Happy)], 0.5f);
  EXPECT_FLOAT_EQ(wistful.emotions[static_cast<size_t>(Emotion::Sad)], 0.5f);
  for (float w : library->find("custom")->emotions) EXPECT_EQ(w, 0.0f);
}

// ---- refused input ----

std::string errorOf(std::string_view json) {
  auto library = ExpressionLibrary::parse(json, "bad.json");
  return library ? std::string("(accepted)") : library.error().message;
}

TEST(ExpressionLibraryValidity, UnknownActionUnitNamesFilePathAndKnownNames) {
  const std::string message =
      errorOf(R"({"version":1,"expressions":{"smirk":{"actionUnits":{"AU12_LipCornerPuller":1}}}})");
  EXPECT_NE(message.find("bad.json: /expressions/smirk/actionUnits/AU12_LipCornerPuller: unknown action unit"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("AU12_LipCornerPuller_L"), std::string::npos) << message;
}

TEST(ExpressionLibraryValidity, WeightsMustBeFiniteNumbersInUnitRange) {
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"actionUnits":{"AU4_BrowLowerer":1.5}}}})")
                .find("/expressions/x/actionUnits/AU4_BrowLowerer: weight 1.5 is outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"actionUnits":{"AU4_BrowLowerer":-0.1}}}})").find("outside"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"actionUnits":{"AU4_BrowLowerer":1e999}}}})")
                .find("bad.json: invalid JSON: number overflow parsing '1e999'"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"actionUnits":{"AU4_BrowLowerer":"high"}}}})")
                .find("bad.json: /expressions/x/actionUnits/AU4_BrowLowerer: expected a number, got string"),
            std::string::npos);
  // JSON has no NaN literal: the parser names the position.
  const std::string nan = errorOf("{\"version\":1,\n\"expressions\":{\"x\":{\"actionUnits\":{\"AU4_BrowLowerer\":NaN}}}}");
  EXPECT_NE(nan.find("bad.json: invalid JSON"), std::string::npos) << nan;
  EXPECT_NE(nan.find("line 2"), std::string::npos) << nan;
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"emotions":{"happy":2}}}})")
                .find("/expressions/x/emotions/happy: weight 2 is outside"),
            std::string::npos);
}

TEST(ExpressionLibraryValidity, VersionAndStructureAreChecked) {
  EXPECT_NE(errorOf(R"({"expressions":{}})").find("bad.json: /: missing \"version\""), std::string::npos);
  EXPECT_NE(errorOf(R"({"version":2,"expressions":{}})").find("/version: unsupported version 2"), std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1})").find("bad.json: /: missing \"expressions\""), std::string::npos);
  EXPECT_NE(errorOf(R"([1,2])").find("bad.json: /: expected a JSON object at the top level"), std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"actionUnit":{}}}})").find("/expressions/x/actionUnit: unknown key"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"emotions":{"joy":1}}}})").find("/expressions/x/emotions/joy: unknown emotion"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"components":["happy","bored"]}}})")
                .find("/expressions/x/components/1: 'bored' is not a basic emotion"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"components":["happy"]}}})").find("at least 2 components"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":{"components":["sad","sad"]}}})").find("listed twice"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"version":1,"expressions":{"x":[]}})").find("bad.json: /expressions/x: expected an object, got array"),
            std::string::npos);
}

// The fuzzer's seed (fuzz/seeds/expressions) is a well-formed library with a compound.
TEST(ExpressionLibrary, FuzzSeedLoads) {
  auto library = ExpressionLibrary::load(testing_support::sourceDir() / "fuzz" / "seeds" / "expressions" / "compound.json");
  ASSERT_TRUE(library) << library.error().message;
  EXPECT_TRUE(library->isCompound("happily_sad"));
}

TEST(ExpressionLibraryValidity, MissingAndBrokenFilesNameTheFile) {
  const std::filesystem::path dir = testing_support::freshTempDir("expression_library");
  auto missing = ExpressionLibrary::load(dir / "absent.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("absent.json: file not found"), std::string::npos) << missing.error().message;

  testing_support::writeFile(dir / "truncated.json", R"({"version":1,"expressions":{"x":)");
  auto truncated = ExpressionLibrary::load(dir / "truncated.json");
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("truncated.json: invalid JSON"), std::string::npos)
      << truncated.error().message;

  testing_support::writeFile(dir / "bad_unit.json", R"({"version":1,"expressions":{"x":{"actionUnits":{"AU99":1}}}})");
  auto badUnit = ExpressionLibrary::load(dir / "bad_unit.json");
  ASSERT_FALSE(badUnit);
  EXPECT_NE(badUnit.error().message.find("bad_unit.json: /expressions/x/actionUnits/AU99: unknown action unit"),
            std::string::npos)
      << badUnit.error().message;
}

TEST(ExpressionLibraryValidity, EvaluateRefusesWrongSizesAndNonFiniteIntensity) {
  auto library = ExpressionLibrary::parse(R"({"version":1,"expressions":{"x":{"actionUnits":{"AU4_BrowLowerer":1}}}})",
                                          "inline.json");
  ASSERT_TRUE(library);
  const ExpressionPreset& x = *library->find("x");
  std::vector<float> shortBuffer(3, 9.0f);
  auto wrong = ExpressionLibrary::evaluate(x, 1.0f, shortBuffer);
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("3 entries, expected " + std::to_string(actionUnits().size())),
            std::string::npos)
      << wrong.error().message;
  EXPECT_EQ(shortBuffer[0], 9.0f);  // nothing written
  std::vector<float> weights(actionUnits().size());
  EXPECT_FALSE(ExpressionLibrary::evaluate(x, std::numeric_limits<float>::quiet_NaN(), weights));
  std::vector<float> emotions(kEmotionCount + 1);
  EXPECT_FALSE(ExpressionLibrary::evaluateEmotions(x, 1.0f, emotions));
}

}  // namespace
}  // namespace facial
