// `facial rig`: the rig mapping report of a model, as text and JSON.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/scene/gltf_writer.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

TEST(RigCommand, TextReportNamesSchemeAndUnmappedTargetsAndInputs) {
  const std::filesystem::path face = writeTestFace("rig_command_face");
  const CommandOutput run = runFacial({"rig", face.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find(face.string() + " (glTF): 5 morph weight(s), 4 driven"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("scheme: FACS action units"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("unmapped targets (1): custom_shape"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("unmapped inputs ("), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("AU45_Blink_L"), std::string::npos) << "the test face has no blink target:\n" << run.out;
}

TEST(RigCommand, JsonReportParses) {
  const std::filesystem::path face = writeTestFace("rig_command_face");
  const CommandOutput run = runFacial({"rig", face.string(), "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << run.out;
  EXPECT_EQ(report["model"], face.string());
  EXPECT_EQ(report["scheme"], "FACS action units");
  EXPECT_EQ(report["targetCount"], 5);
  EXPECT_EQ(report["drivenTargetCount"], 4);
  EXPECT_EQ(report["unmappedTargets"], nlohmann::json::array({"custom_shape"}));
  EXPECT_TRUE(report["unmappedInputs"].is_array());
  EXPECT_TRUE(report["notes"].is_array());
}

TEST(RigCommand, RigMapFileOverridesDetection) {
  const std::filesystem::path face = writeTestFace("rig_command_rigmap");
  const std::filesystem::path rigmap = face.parent_path() / "custom.json";
  testing_support::writeFile(rigmap, R"({"version": 1, "model": "test_face",
      "map": {"happy": [{"target": "custom_shape", "weight": 1.0}]}})");
  const CommandOutput run = runFacial({"rig", face.string(), "--rigmap", rigmap.string(), "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << run.out;
  EXPECT_EQ(report["drivenTargetCount"], 1);
  EXPECT_EQ(report["unmappedTargets"].size(), 4u);
}

TEST(RigCommand, FacecapIsArkitWithGazeLeftFree) {
  FACIAL_REQUIRE_SHARED();
  const CommandOutput run = runFacial({"rig", facecapPath().string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("scheme: ARKit 52 blend shapes (52 of 52 ARKit names"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("eyeLookUp_L"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("note: "), std::string::npos) << run.out;
}

// ---- refused input ----

TEST(RigCommandValidity, MissingModelFileIsNamed) {
  const std::string missing = (testing_support::freshTempDir("rig_command_missing") / "nowhere.glb").string();
  const CommandOutput run = runFacial({"rig", missing});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("facial rig: error: " + missing), std::string::npos) << run.err;
}

TEST(RigCommandValidity, UnrecognisedTargetNamesSuggestARigMap) {
  eng::Model model = makeTestFace();
  model.meshes[0].targetNames = {"foo", "bar", "baz", "qux", "quux"};
  const std::filesystem::path path = testing_support::freshTempDir("rig_command_odd") / "odd.glb";
  ASSERT_TRUE(eng::saveModel(model, path));
  const CommandOutput run = runFacial({"rig", path.string()});
  EXPECT_NE(run.exitCode, 0);
  const std::string expected = "facial rig: error: " + path.string() + ": rig mapping: no scheme recognises the 5";
  EXPECT_NE(run.err.find(expected), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("rigmaps/odd.json"), std::string::npos) << run.err;
}

TEST(RigCommandValidity, ModelIsRequired) {
  const CommandOutput run = runFacial({"rig"});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("model is required"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace cli_test
