// Dataset specs: the example reads and checks; every bad field is refused
// with one line naming the spec file and the field.
#include <string>

#include <algorithm>

#include <gtest/gtest.h>

#include "app/face_setup.h"
#include "dataset/dataset_spec.h"
#include "tests/common/test_support.h"

namespace dataset {
namespace {

const std::string kSource = "s.json";

// The spec `json` parsed and checked; the error message, or "" when it passed.
std::string problemWith(const std::string& json) {
  auto spec = parseDatasetSpec(json, kSource, testing_support::sourceDir());
  if (!spec) return spec.error().message;
  auto checked = checkDatasetSpec(*spec, app::defaultExpressionsPath());
  return checked ? "" : checked.error().message;
}

TEST(DatasetSpec, TheExampleReadsAndChecks) {
  auto spec = readDatasetSpec(testing_support::sourceDir() / "data/datasets/example.json");
  ASSERT_TRUE(spec) << spec.error().message;
  auto checked = checkDatasetSpec(*spec, app::defaultExpressionsPath());
  EXPECT_TRUE(checked) << checked.error().message;
  EXPECT_GE(spec->count, 50u);
  EXPECT_LE(spec->count, 500u);  // a few hundred images at most
  EXPECT_EQ(spec->width, 256u);
  // Compound emotions as people write them, stored as the presets' names.
  EXPECT_NE(std::find(spec->emotions.begin(), spec->emotions.end(), "happily_surprised"), spec->emotions.end());
}

TEST(DatasetSpec, AMinimalSpecTakesTheDefaults) {
  EXPECT_EQ(problemWith(R"({"count": 3})"), "");
  auto spec = parseDatasetSpec(R"({"count": 3, "yaw": 10})", kSource, ".");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->yaw.min, 10.0f);
  EXPECT_EQ(spec->yaw.max, 10.0f);
  EXPECT_EQ(spec->models, std::vector<std::string>{"head"});
}

TEST(DatasetSpec, UnknownNamesAreNamedWithTheirField) {
  EXPECT_NE(problemWith(R"({"count": 3, "emotions": ["happy", "smug"]})").find("s.json: /emotions/1: unknown emotion 'smug' (known: neutral, happy"),
            std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "models": ["head", "nowhere.glb"]})").find("s.json: /models/1: no such model file"),
            std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "lights": ["disco"]})").find("s.json: /lights/0: unknown light rig 'disco'"),
            std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "backgrounds": ["#12"]})").find("s.json: /backgrounds/0:"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "colour": 1})").find("s.json: "), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "colour": 1})").find("colour"), std::string::npos);
}

TEST(DatasetSpec, ImpossibleRangesAndCountsAreRefused) {
  EXPECT_NE(problemWith(R"({"count": 3, "yaw": [30, -30]})").find("s.json: /yaw: min 30 is above max -30"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "intensity": [0.2, 1.5]})").find("s.json: /intensity: [0.2, 1.5] is outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 0})").find("s.json: /count: must be at least 1"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 1000000000000})").find("s.json: /count: 1000000000000 is over the limit"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": -4})").find("/count: must not be negative"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 2.5})").find("/count: must be a whole number"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "size": "0x64"})").find("s.json: /size: 0x64 is outside"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "size": "big"})").find("/size"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "emotions": []})").find("s.json: /emotions: is empty"), std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "auMix": {"units": [3, 1]}})").find("s.json: /auMix/units: min 3 is above max 1"),
            std::string::npos);
  EXPECT_NE(problemWith(R"({"count": 3, "yaw": [0, 1, 2]})").find("/yaw"), std::string::npos);
  EXPECT_NE(problemWith("{\"count\": 3,").find("s.json"), std::string::npos);
}

TEST(DatasetSpec, EmotionNamesAsPeopleWriteThem) {
  EXPECT_EQ(canonicalEmotionName("happily surprised"), "happily_surprised");
  EXPECT_EQ(canonicalEmotionName("Sadly-Angry"), "sadly_angry");
}

TEST(DatasetSpec, RangesFromFlags) {
  auto range = parseRange("-30:30", "--yaw");
  ASSERT_TRUE(range);
  EXPECT_EQ(range->min, -30.0f);
  EXPECT_EQ(range->max, 30.0f);
  auto one = parseRange("12.5", "--yaw");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->min, 12.5f);
  auto bad = parseRange("left:right", "--yaw");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("--yaw: 'left:right'"), std::string::npos);
}

TEST(DatasetSpec, TheHashFollowsTheContentNotTheFile) {
  auto a = parseDatasetSpec(R"({"count": 3, "seed": 1})", "a.json", ".");
  auto b = parseDatasetSpec(R"({"seed": 1, "count": 3})", "b.json", "elsewhere");
  auto c = parseDatasetSpec(R"({"count": 3, "seed": 2})", "a.json", ".");
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(specHash(*a), specHash(*b));
  EXPECT_NE(specHash(*a), specHash(*c));
}

}  // namespace
}  // namespace dataset
