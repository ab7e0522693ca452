// data/head_landmarks.json format: what a valid file becomes (mirrored
// landmarks, symmetric parts, masks, detail layers), and one clear error per
// kind of bad input, naming the file, the JSON path and the problem.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "bake/head/head_rig_spec.h"
#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"

namespace {

using nlohmann::json;

// A minimal valid file: every canonical action unit moves one landmark.
json minimalSpec() {
  json j;
  j["format"] = "facial-head-landmarks";
  j["version"] = 1;
  j["landmarks"] = json::array({
      {{"name", "brow_L"}, {"xy", {0.03, 0.03}}, {"mirror", true}},
      {{"name", "lid_upper_L"}, {"feature", "eye_L.upper_lid"}, {"mirror", true}},
      {{"name", "lid_lower_L"}, {"feature", "eye_L.lower_lid"}, {"mirror", true}},
      {{"name", "hinge_L"}, {"position", {0.06, 0.0, -0.01}}, {"mirror", true}},
      {{"name", "chin"}, {"xy", {0.0, -0.07}}},
  });
  j["anchors"] = json::array({{{"name", "crown"}, {"position", {0.0, 0.12, 0.0}}}});
  j["actionUnits"] = json::array();
  for (const facial::ActionUnitInfo& info : facial::actionUnits())
    j["actionUnits"].push_back({{"name", std::string(info.name)}, {"parts", json::array({{{"move", {{"chin", {0.0, -0.001, 0.0}}}}}})}});
  return j;
}

bake::HeadRigSpec parseOk(const json& j) {
  auto spec = bake::parseHeadRigSpec(j.dump(), "test.json");
  EXPECT_TRUE(spec.ok()) << (spec.ok() ? "" : spec.error().message);
  return spec.ok() ? std::move(spec).value() : bake::HeadRigSpec{};
}

std::string parseErrorOfText(const std::string& text) {
  auto spec = bake::parseHeadRigSpec(text, "test.json");
  EXPECT_FALSE(spec.ok()) << "expected a parse error";
  return spec.ok() ? "" : spec.error().message;
}
std::string parseError(const json& j) { return parseErrorOfText(j.dump()); }

// --- results ------------------------------------------------------------------

TEST(HeadRigSpec, MirroredLandmarksAreExpandedWithNegatedX) {
  const bake::HeadRigSpec spec = parseOk(minimalSpec());
  const bake::LandmarkDef* left = spec.findLandmark("brow_L");
  const bake::LandmarkDef* right = spec.findLandmark("brow_R");
  ASSERT_NE(left, nullptr);
  ASSERT_NE(right, nullptr);
  EXPECT_FLOAT_EQ(right->xy.x, -left->xy.x);
  EXPECT_FLOAT_EQ(right->xy.y, left->xy.y);
  EXPECT_EQ(spec.findLandmark("lid_upper_R")->feature, "eye_R.upper_lid");
  EXPECT_FLOAT_EQ(spec.findLandmark("hinge_R")->position.x, -0.06f);
  EXPECT_EQ(spec.findLandmark("chin_R"), nullptr);
  EXPECT_EQ(spec.landmarks.size(), 9u);
}

TEST(HeadRigSpec, SymmetricPartMirrorsMovesPinsAndFreeEntries) {
  json j = minimalSpec();
  j["actionUnits"][0]["parts"][0] = {{"symmetric", true},
                                     {"move", {{"brow_L", {0.001, 0.006, 0.0}}, {"chin", {0.0, 0.001, 0.0}}}},
                                     {"pins", {"hinge_L"}},
                                     {"free", {"lid_upper_L"}}};
  const bake::HeadRigSpec spec = parseOk(j);
  const bake::DeformPartDef& part = spec.actionUnits[0].parts[0];
  ASSERT_EQ(part.moves.size(), 3u);
  const auto right = std::find_if(part.moves.begin(), part.moves.end(), [](auto& m) { return m.landmark == "brow_R"; });
  ASSERT_NE(right, part.moves.end());
  EXPECT_FLOAT_EQ(right->by.x, -0.001f);
  EXPECT_FLOAT_EQ(right->by.y, 0.006f);
  EXPECT_EQ(part.pins, (std::vector<std::string>{"hinge_L", "hinge_R"}));
  EXPECT_EQ(part.free, (std::vector<std::string>{"lid_upper_L", "lid_upper_R"}));
}

TEST(HeadRigSpec, MasksMoveTargetsKernelAndDetailLayersAreRead) {
  json j = minimalSpec();
  j["kernel"] = {{"type", "polyharmonic"}, {"k", 1}};
  j["actionUnits"][5]["parts"][0] = {
      {"mask", {{"parts", {"skin", "teeth_lower"}}, {"jaw", "lower"}, {"side", "left"}, {"radius", 0.01}, {"feather", 0.005}}},
      {"move", {{"lid_upper_L", {{"to", "lid_lower_L"}, {"by", {0.0, -0.0004, 0.0}}}}}}};
  j["detailLayers"] = json::array({{{"layer", "brow_knot"}, {"target", "AU4_BrowLowerer"}, {"strength", 0.5}}});
  const bake::HeadRigSpec spec = parseOk(j);
  EXPECT_EQ(spec.kernel.type, facial::RbfKernelType::Polyharmonic);
  const bake::DeformPartDef& part = spec.actionUnits[5].parts[0];
  EXPECT_TRUE(part.mask.includes(bake::HeadPart::Skin));
  EXPECT_TRUE(part.mask.includes(bake::HeadPart::TeethLower));
  EXPECT_FALSE(part.mask.includes(bake::HeadPart::Mouth));
  EXPECT_EQ(part.mask.jaw, bake::MaskDef::Jaw::Lower);
  EXPECT_EQ(part.mask.side, bake::MaskDef::Side::Left);
  EXPECT_FLOAT_EQ(part.mask.radius, 0.01f);
  ASSERT_EQ(part.moves.size(), 1u);
  EXPECT_EQ(part.moves[0].to, "lid_lower_L");
  EXPECT_FLOAT_EQ(part.moves[0].by.y, -0.0004f);
  ASSERT_EQ(spec.detailLayers.size(), 1u);
  EXPECT_EQ(spec.detailLayers[0].target, "AU4_BrowLowerer");
  EXPECT_FLOAT_EQ(spec.detailLayers[0].strength, 0.5f);
}

TEST(HeadRigSpec, ProjectFileDefinesEveryCanonicalActionUnit) {
  auto spec = bake::loadHeadRigSpec(testing_support::sourceDir() / "data" / "head_landmarks.json");
  ASSERT_TRUE(spec.ok()) << spec.error().message;
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) {
    const auto found = std::find_if(spec->actionUnits.begin(), spec->actionUnits.end(),
                                    [&](const bake::ActionUnitDef& a) { return a.name == info.name; });
    EXPECT_NE(found, spec->actionUnits.end()) << info.name;
  }
}

// --- bad input ----------------------------------------------------------------

TEST(HeadRigSpecErrors, MissingFileNamesThePath) {
  const auto path = testing_support::freshTempDir("head_rig_spec_missing") / "absent.json";
  auto spec = bake::loadHeadRigSpec(path);
  ASSERT_FALSE(spec.ok());
  EXPECT_NE(spec.error().message.find(path.string()), std::string::npos) << spec.error().message;
  EXPECT_NE(spec.error().message.find("cannot open"), std::string::npos) << spec.error().message;
}

TEST(HeadRigSpecErrors, FileErrorsNameTheFile) {
  const auto dir = testing_support::freshTempDir("head_rig_spec_file");
  json j = minimalSpec();
  j["landmarks"][0]["xy"] = {0.03};
  testing_support::writeFile(dir / "broken.json", j.dump());
  auto spec = bake::loadHeadRigSpec(dir / "broken.json");
  ASSERT_FALSE(spec.ok());
  EXPECT_NE(spec.error().message.find((dir / "broken.json").string()), std::string::npos) << spec.error().message;
  EXPECT_NE(spec.error().message.find("/landmarks/0/xy"), std::string::npos) << spec.error().message;
}

TEST(HeadRigSpecErrors, InvalidJson) {
  const std::string e = parseErrorOfText("{\"format\": ");
  EXPECT_NE(e.find("test.json"), std::string::npos) << e;
  EXPECT_NE(e.find("invalid JSON"), std::string::npos) << e;
}

TEST(HeadRigSpecErrors, WrongFormatTag) {
  json j = minimalSpec();
  j["format"] = "something-else";
  EXPECT_NE(parseError(j).find("test.json: /format: expected \"facial-head-landmarks\""), std::string::npos);
}

TEST(HeadRigSpecErrors, UnknownKeyIsReportedWithItsPath) {
  json j = minimalSpec();
  j["landmarks"][1]["fetaure"] = "typo";
  EXPECT_NE(parseError(j).find("test.json: /landmarks/1/fetaure: unknown key"), std::string::npos);
}

TEST(HeadRigSpecErrors, VectorOfWrongLength) {
  json j = minimalSpec();
  j["landmarks"][3]["position"] = {0.06, 0.0};
  EXPECT_NE(parseError(j).find("test.json: /landmarks/3/position: expected an array of 3 numbers"), std::string::npos);
}

TEST(HeadRigSpecErrors, NonNumberCoordinate) {
  json j = minimalSpec();
  j["landmarks"][0]["xy"] = {0.03, "high"};
  EXPECT_NE(parseError(j).find("test.json: /landmarks/0/xy/1: expected a number, got string"), std::string::npos);
}

TEST(HeadRigSpecErrors, LandmarkWithTwoDefinitions) {
  json j = minimalSpec();
  j["landmarks"][4]["position"] = {0.0, -0.07, 0.08};
  EXPECT_NE(parseError(j).find("needs exactly one of"), std::string::npos);
}

TEST(HeadRigSpecErrors, DuplicateLandmarkName) {
  json j = minimalSpec();
  j["landmarks"].push_back({{"name", "chin"}, {"xy", {0.0, -0.06}}});
  EXPECT_NE(parseError(j).find("/landmarks/5/name: duplicate landmark \"chin\""), std::string::npos);
}

TEST(HeadRigSpecErrors, MirrorOfACentreLandmark) {
  json j = minimalSpec();
  j["landmarks"][4]["mirror"] = true;
  EXPECT_NE(parseError(j).find("/landmarks/4/mirror: only left-side landmarks"), std::string::npos);
}

TEST(HeadRigSpecErrors, UnknownLandmarkInAMove) {
  json j = minimalSpec();
  j["actionUnits"][2]["parts"][0]["move"] = {{"nose_tipp", {0.0, 0.001, 0.0}}};
  EXPECT_NE(parseError(j).find("/actionUnits/2/parts/0/move/nose_tipp: unknown landmark \"nose_tipp\""),
            std::string::npos);
}

TEST(HeadRigSpecErrors, UnknownMoveTarget) {
  json j = minimalSpec();
  j["actionUnits"][2]["parts"][0]["move"] = {{"chin", {{"to", "nowhere"}}}};
  EXPECT_NE(parseError(j).find("/actionUnits/2/parts/0/move/chin/to: unknown landmark \"nowhere\""), std::string::npos);
}

TEST(HeadRigSpecErrors, NonCanonicalActionUnitName) {
  json j = minimalSpec();
  j["actionUnits"][0]["name"] = "AU1_InnerBrow";
  EXPECT_NE(parseError(j).find("/actionUnits/0/name: \"AU1_InnerBrow\" is not a channel"), std::string::npos);
}

TEST(HeadRigSpecErrors, MissingActionUnit) {
  json j = minimalSpec();
  j["actionUnits"].erase(j["actionUnits"].size() - 1);
  EXPECT_NE(parseError(j).find("/actionUnits: action unit \"AU45_Blink_R\" is missing"), std::string::npos);
}

TEST(HeadRigSpecErrors, ActionUnitDefinedTwice) {
  json j = minimalSpec();
  j["actionUnits"].push_back(j["actionUnits"][0]);
  EXPECT_NE(parseError(j).find("defined twice"), std::string::npos);
}

TEST(HeadRigSpecErrors, BadMaskValues) {
  json j = minimalSpec();
  j["actionUnits"][0]["parts"][0]["mask"] = {{"parts", {"skin", "eyebrows"}}};
  EXPECT_NE(parseError(j).find("/actionUnits/0/parts/0/mask/parts/1: unknown part \"eyebrows\""), std::string::npos);
  j["actionUnits"][0]["parts"][0]["mask"] = {{"jaw", "middle"}};
  EXPECT_NE(parseError(j).find("/actionUnits/0/parts/0/mask/jaw: expected \"upper\""), std::string::npos);
  j["actionUnits"][0]["parts"][0]["mask"] = {{"radius", -0.01}};
  EXPECT_NE(parseError(j).find("/actionUnits/0/parts/0/mask/radius: must be > 0"), std::string::npos);
}

TEST(HeadRigSpecErrors, SymmetricPartWithOneSidedMask) {
  json j = minimalSpec();
  j["actionUnits"][0]["parts"][0]["symmetric"] = true;
  j["actionUnits"][0]["parts"][0]["mask"] = {{"side", "left"}};
  EXPECT_NE(parseError(j).find("/actionUnits/0/parts/0/symmetric: a symmetric part cannot have a one-sided mask"),
            std::string::npos);
}

TEST(HeadRigSpecErrors, EmptyMove) {
  json j = minimalSpec();
  j["actionUnits"][0]["parts"][0]["move"] = json::object();
  EXPECT_NE(parseError(j).find("/actionUnits/0/parts/0/move: no landmark is moved"), std::string::npos);
}

TEST(HeadRigSpecErrors, UnknownDetailLayerAndTarget) {
  json j = minimalSpec();
  j["detailLayers"] = json::array({{{"layer", "freckles"}, {"target", "AU4_BrowLowerer"}}});
  EXPECT_NE(parseError(j).find("/detailLayers/0/layer: unknown detail layer \"freckles\""), std::string::npos);
  j["detailLayers"] = json::array({{{"layer", "flush"}, {"target", "Anger"}}});
  EXPECT_NE(parseError(j).find("/detailLayers/0/target: \"Anger\" is not an action unit channel"), std::string::npos);
}

TEST(HeadRigSpecErrors, UnknownKernel) {
  json j = minimalSpec();
  j["kernel"] = {{"type", "gaussian"}};
  EXPECT_NE(parseError(j).find("/kernel/type: expected biharmonic"), std::string::npos);
}

}  // namespace
