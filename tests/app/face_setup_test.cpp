// FaceSetup: a model, its rig mapping and the project's presets turned into
// the model's flat weights (defaults as the base, driven targets overwritten,
// intensity clamped), and the data-folder look-up.
#include "app/face_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace app {
namespace {

using namespace cli_test;

class TestFaceSetup : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = app::FaceSetup::load({.model = writeTestFace("face_setup")});
    ASSERT_TRUE(loaded) << loaded.error().message;
    face_.emplace(std::move(*loaded));
  }
  std::vector<float> posed(std::string_view expression, float intensity) {
    std::vector<float> weights(face_->weightCount(), -1.0f);
    auto preset = face_->findExpression(expression);
    EXPECT_TRUE(preset) << preset.error().message;
    if (!preset) return weights;
    auto ok = face_->expressionWeights(**preset, intensity, weights);
    EXPECT_TRUE(ok) << ok.error().message;
    return weights;
  }
  std::optional<app::FaceSetup> face_;
};

TEST_F(TestFaceSetup, KnowsTheModelItsRigAndThePresets) {
  EXPECT_EQ(face_->name(), "test_face");
  EXPECT_EQ(face_->weightCount(), 5u);
  EXPECT_EQ(face_->rig().scheme(), facial::RigScheme::ActionUnits);
  ASSERT_EQ(face_->baseWeights().size(), 5u);
  EXPECT_FLOAT_EQ(face_->baseWeights()[kBrowLower], 0.3f);
  EXPECT_FLOAT_EQ(face_->baseWeights()[kCustom], 0.4f);
  EXPECT_NE(face_->expressions().find("happy"), nullptr);
}

TEST_F(TestFaceSetup, BasicPresetsAreNeutralAndTheSixEmotionsInOrder) {
  std::vector<std::string> names;
  for (const facial::ExpressionPreset* p : face_->presets(false)) names.push_back(p->name);
  EXPECT_EQ(names, (std::vector<std::string>{"neutral", "happy", "sad", "surprise", "fear", "anger", "disgust"}));
  const std::vector<const facial::ExpressionPreset*> compounds = face_->presets(true);
  EXPECT_GE(compounds.size(), 4u);
  for (const facial::ExpressionPreset* p : compounds) EXPECT_TRUE(p->isCompound()) << p->name;
}

TEST_F(TestFaceSetup, DrivenTargetsAreOverwrittenOthersKeepTheirDefaults) {
  // Driven targets reach the preset's strength as calibrated for this face
  // (its shapes move far for its size, so the calibration damps them).
  const std::vector<float> happy = posed("happy", 1.0f);
  EXPECT_GT(happy[kSmileLeft], 0.5f);
  EXPECT_FLOAT_EQ(happy[kSmileRight], happy[kSmileLeft]);
  EXPECT_FLOAT_EQ(happy[kBrowLower], 0.0f) << "driven: the default 0.3 is replaced by the preset's 0";
  EXPECT_FLOAT_EQ(happy[kCustom], 0.4f) << "no channel drives it: the model's default stays";

  const std::vector<float> anger = posed("anger", 1.0f);
  EXPECT_GT(anger[kBrowLower], 0.5f);
  EXPECT_FLOAT_EQ(anger[kSmileLeft], 0.0f);

  const std::vector<float> neutral = posed("neutral", 1.0f);
  EXPECT_EQ(neutral, (std::vector<float>{0.0f, 0.0f, 0.0f, 0.0f, 0.4f}));
}

TEST_F(TestFaceSetup, IntensityScalesAndIsClampedToUnitRange) {
  const std::vector<float> half = posed("surprise", 0.5f);
  const std::vector<float> full = posed("surprise", 1.0f);
  ASSERT_GT(full[kJawDrop], 0.0f);
  EXPECT_FLOAT_EQ(half[kJawDrop], 0.5f * full[kJawDrop]);
  EXPECT_EQ(posed("surprise", 7.0f), full);
  EXPECT_EQ(posed("surprise", -2.0f), posed("neutral", 1.0f));
  EXPECT_EQ(posed("surprise", 0.0f), posed("neutral", 1.0f));
}

TEST_F(TestFaceSetup, RepeatedPosesDoNotLeakIntoEachOther) {
  const std::vector<float> happyFirst = posed("happy", 1.0f);
  (void)posed("anger", 1.0f);
  EXPECT_EQ(posed("happy", 1.0f), happyFirst);
}

TEST_F(TestFaceSetup, UnknownExpressionListsTheAvailableNames) {
  auto preset = face_->findExpression("elation");
  ASSERT_FALSE(preset);
  EXPECT_NE(preset.error().message.find("unknown expression 'elation'; available: neutral, happy, sad"),
            std::string::npos)
      << preset.error().message;
  EXPECT_NE(preset.error().message.find("angrily_disgusted"), std::string::npos) << "compounds are listed too";
}

TEST_F(TestFaceSetup, NonFiniteIntensityAndWrongSizeAreRefusedWithoutWriting) {
  const facial::ExpressionPreset& happy = **face_->findExpression("happy");
  std::vector<float> weights(5, -1.0f);
  auto nan = face_->expressionWeights(happy, std::numeric_limits<float>::quiet_NaN(), weights);
  ASSERT_FALSE(nan);
  EXPECT_NE(nan.error().message.find("intensity nan is not a finite number"), std::string::npos)
      << nan.error().message;
  EXPECT_FALSE(face_->expressionWeights(happy, std::numeric_limits<float>::infinity(), weights));
  EXPECT_EQ(weights, std::vector<float>(5, -1.0f));

  std::vector<float> tooShort(3, -1.0f);
  auto wrongSize = face_->expressionWeights(happy, 1.0f, tooShort);
  ASSERT_FALSE(wrongSize);
  EXPECT_NE(wrongSize.error().message.find("3 weights given, test_face has 5"), std::string::npos)
      << wrongSize.error().message;
  EXPECT_EQ(tooShort, std::vector<float>(3, -1.0f));
}

// The programs draw a face dressed (importers/face_dressing.h): the test
// face made plaster-white gets a dressed copy to upload, and model() -- what
// the rig reads and the editor saves -- stays as the file has it.
TEST(FaceSetupDisplay, ThePlasterFaceIsDrawnDressedAndKeptAsLoaded) {
  eng::Model plaster = makeTestFace();
  for (eng::Material& material : plaster.materials) material.baseColorFactor = glm::vec4(1.0f);
  const std::filesystem::path path = testing_support::freshTempDir("face_setup_plaster") / "plaster.glb";
  ASSERT_TRUE(eng::saveModel(plaster, path));
  auto face = app::FaceSetup::load({.model = path});
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_NE(&face->displayModel(), &face->model());
  EXPECT_GT(face->displayModel().materials.size(), face->model().materials.size());
  EXPECT_EQ(face->model().materials.size(), plaster.materials.size());
  EXPECT_EQ(face->model().materials[0].baseColorFactor, glm::vec4(1.0f));

  auto undressed = app::FaceSetup::load({.model = path, .dressForDisplay = false});
  ASSERT_TRUE(undressed) << undressed.error().message;
  EXPECT_EQ(&undressed->displayModel(), &undressed->model());
}

TEST(FaceSetupValidity, MissingModelFileIsNamed) {
  const std::filesystem::path missing = testing_support::freshTempDir("face_setup_missing") / "nowhere.glb";
  auto face = app::FaceSetup::load({.model = missing});
  ASSERT_FALSE(face);
  EXPECT_NE(face.error().message.find(missing.string()), std::string::npos) << face.error().message;
}

TEST(FaceSetupValidity, BrokenPresetFileIsNamed) {
  const std::filesystem::path dir = testing_support::freshTempDir("face_setup_presets");
  testing_support::writeFile(dir / "presets.json",
                             R"({"version": 1, "expressions": {"x": {"actionUnits": {"AU99": 1}}}})");
  auto face =
      app::FaceSetup::load({.model = writeTestFace("face_setup_presets_model"), .expressions = dir / "presets.json"});
  ASSERT_FALSE(face);
  EXPECT_NE(face.error().message.find("presets.json"), std::string::npos) << face.error().message;
  EXPECT_NE(face.error().message.find("AU99"), std::string::npos) << face.error().message;
}

TEST(FaceSetupValidity, ModelNoSchemeRecognisesNamesTheFileAndSuggestsARigMap) {
  eng::Model model = makeTestFace();
  model.meshes[0].targetNames = {"foo", "bar", "baz", "qux", "quux"};
  const std::filesystem::path path = testing_support::freshTempDir("face_setup_unknown_rig") / "odd.glb";
  ASSERT_TRUE(eng::saveModel(model, path));
  auto face = app::FaceSetup::load({.model = path});
  ASSERT_FALSE(face);
  EXPECT_NE(face.error().message.find(path.string() + ": rig mapping: no scheme recognises"), std::string::npos)
      << face.error().message;
  EXPECT_NE(face.error().message.find("rigmaps/odd.json"), std::string::npos) << face.error().message;
}

TEST(FaceSetupData, DataFolderComesFromTheEnvironmentElseTheSourceTree) {
  const char* saved = std::getenv("FACIAL_DATA_DIR");
  const std::string previous = saved ? saved : "";
  ::unsetenv("FACIAL_DATA_DIR");
  EXPECT_EQ(app::dataDirectory(), testing_support::sourceDir() / "data");
  EXPECT_EQ(app::defaultModelPath(), testing_support::sourceDir() / "data" / "head.glb");
  EXPECT_EQ(app::defaultExpressionsPath(), testing_support::sourceDir() / "data" / "expressions.json");
  ::setenv("FACIAL_DATA_DIR", "/opt/facial-data", 1);
  EXPECT_EQ(app::dataDirectory(), std::filesystem::path("/opt/facial-data"));
  EXPECT_EQ(app::defaultModelPath(), std::filesystem::path("/opt/facial-data/head.glb"));
  if (saved) ::setenv("FACIAL_DATA_DIR", previous.c_str(), 1);
  else ::unsetenv("FACIAL_DATA_DIR");
}

TEST(FaceSetupData, ModelNameIsTheFileStem) {
  EXPECT_EQ(app::modelNameOf("/a/b/facecap.glb"), "facecap");
  EXPECT_EQ(app::modelNameOf("head.gltf"), "head");
}

TEST(FaceSetupData, BuiltInHeadsRigMapRaisesItsJawOnTopOfTheMeasuredScale) {
  // data/rigmaps/head.json: the head's jaw drop is measured like any rig's,
  // then raised (its lips and teeth fill the gap a scanned face shows dark).
  auto model = eng::loadModel(app::defaultModelPath());
  ASSERT_TRUE(model) << model.error().message;
  auto withMap = app::buildModelRig(*model);
  ASSERT_TRUE(withMap) << withMap.error().message;
  auto jaw = [](const facial::RigCalibration& c) {
    for (const facial::ActionUnitCalibration& u : c.units)
      if (u.channel == "AU26_JawDrop") return u;
    return facial::ActionUnitCalibration{};
  };
  // The scale the measurement alone gives, within the calibration's own bounds.
  const facial::RigCalibrationOptions bounds;
  auto measuredScale = [&](const facial::ActionUnitCalibration& u) {
    return std::clamp(u.reference / u.reach, bounds.minScale, bounds.maxScale);
  };
  const facial::ActionUnitCalibration jawUnit = jaw(*withMap);
  ASSERT_GT(jawUnit.reach, 0.0f);
  EXPECT_NEAR(jawUnit.scale, measuredScale(jawUnit) * 1.6f, 1e-4f);
  for (const facial::ActionUnitCalibration& u : withMap->units) {
    if (u.channel == "AU26_JawDrop" || !(u.reference > 0.0f)) continue;
    EXPECT_NEAR(u.scale, measuredScale(u), 1e-4f) << u.channel << " is not overridden";
  }
}

// The same head saved elsewhere under the same name (a user's head.glb) is
// another face: the map found by its name only calibrates the built-in one.
TEST(FaceSetupData, AnotherFaceCalledHeadIsNotCalibratedAsTheBuiltInHead) {
  auto model = eng::loadModel(app::defaultModelPath());
  ASSERT_TRUE(model) << model.error().message;
  auto jawScale = [](const facial::RigCalibration& c) {
    for (const facial::ActionUnitCalibration& u : c.units)
      if (u.channel == "AU26_JawDrop") return u.scale;
    return 0.0f;
  };
  auto builtIn = app::buildModelRig(*model);
  ASSERT_TRUE(builtIn) << builtIn.error().message;
  model->sourcePath = (testing_support::freshTempDir("face_setup_another_head") / "head.glb").string();
  auto another = app::buildModelRig(*model);
  ASSERT_TRUE(another) << another.error().message;
  ASSERT_GT(jawScale(*another), 0.0f);
  EXPECT_NEAR(jawScale(*builtIn), jawScale(*another) * 1.6f, 1e-4f);
}

TEST(FaceSetupShared, FacecapIsDrivenThroughTheArkitScheme) {
  FACIAL_REQUIRE_SHARED();
  auto face = app::FaceSetup::load({.model = testing_support::sharedDir() / "assets" / "facecap.glb"});
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->rig().scheme(), facial::RigScheme::Arkit52);
  std::vector<float> weights(face->weightCount());
  ASSERT_TRUE(face->expressionWeights(**face->findExpression("happy"), 1.0f, weights));
  const int smile = face->layout().find(2, "mouthSmile_L"), gaze = face->layout().find(2, "eyeLookDown_L");
  ASSERT_GE(smile, 0);
  ASSERT_GE(gaze, 0);
  EXPECT_GT(weights[smile], 0.85f) << "full smile, calibrated to facecap's strong mouthSmile";
  EXPECT_LE(weights[smile], 1.0f);
  EXPECT_FLOAT_EQ(weights[gaze], 0.0f) << "gaze is no FACS channel, and ARKit shapes rest at 0: the file's default "
                                          "weights are a captured frame, not the neutral face";
  const std::vector<float> defaults = face->layout().defaults();
  EXPECT_GT(defaults[size_t(gaze)], 0.3f) << "the file's default (eyes looking down) is still what the model says";
}

}  // namespace
}  // namespace app
