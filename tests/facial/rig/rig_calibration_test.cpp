// Per-rig action-unit strength calibration: validity cases (sizes, bad
// reaches, overrides) apart from result cases (scaling toward the reference,
// bounds, blinks untouched, overrides applied).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

// A FACS-named rig: one target per channel, identity gains.
RigMapping facsRig(std::vector<std::string> names) {
  auto rig = buildRigMapping(names, RigScheme::ActionUnits);
  EXPECT_TRUE(rig) << rig.error().message;
  return std::move(*rig);
}

const std::vector<std::string> kNames = {"AU12_LipCornerPuller_L", "AU26_JawDrop", "AU45_Blink_L", "AU4_BrowLowerer"};

float gainOf(const RigMapping& rig, std::string_view channel) {
  const auto gains = rig.gains(*actionUnitIndex(channel));
  return gains.empty() ? 0.0f : gains[0];
}

TEST(RigCalibrationValidity, ReachCountMustMatchTheTargets) {
  const RigMapping rig = facsRig(kNames);
  const std::vector<float> reach(3, 0.05f);
  auto calibrated = calibrateRig(rig, reach);
  ASSERT_FALSE(calibrated);
  EXPECT_NE(calibrated.error().message.find("3 target reaches for 4 targets"), std::string::npos)
      << calibrated.error().message;
}

TEST(RigCalibrationValidity, NonFiniteOrNegativeReachIsRefused) {
  const RigMapping rig = facsRig(kNames);
  EXPECT_FALSE(calibrateRig(rig, std::vector<float>{0.1f, NAN, 0.1f, 0.1f}));
  EXPECT_FALSE(calibrateRig(rig, std::vector<float>{0.1f, -1.0f, 0.1f, 0.1f}));
}

TEST(RigCalibrationValidity, OverrideMustNameAnActionUnit) {
  const RigMapping rig = facsRig(kNames);
  RigCalibrationOptions options;
  options.overrides = {{"AU99_Nothing", 1.2f}};
  auto calibrated = calibrateRig(rig, std::vector<float>(4, 0.05f), options);
  ASSERT_FALSE(calibrated);
  EXPECT_NE(calibrated.error().message.find("AU99_Nothing"), std::string::npos);
}

TEST(RigCalibration, WeakRowsAreRaisedStrongRowsDampedWithinBounds) {
  const RigMapping rig = facsRig(kNames);
  // Smile reaches half its reference, the jaw twice: scaled by 2 (bounded to 1.6) and 0.5 (bounded to 0.6).
  const float smileRef = referenceReach("AU12_LipCornerPuller_L"), jawRef = referenceReach("AU26_JawDrop");
  const float browRef = referenceReach("AU4_BrowLowerer");
  auto calibrated = calibrateRig(rig, std::vector<float>{smileRef * 0.5f, jawRef * 2.0f, 0.2f, browRef * 1.25f});
  ASSERT_TRUE(calibrated) << calibrated.error().message;
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU12_LipCornerPuller_L"), 1.6f);
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU26_JawDrop"), 0.6f);
  EXPECT_NEAR(gainOf(calibrated->rig, "AU4_BrowLowerer"), 0.8f, 1e-5f);
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU45_Blink_L"), 1.0f) << "a blink closes the lid whatever its reach";
  EXPECT_FALSE(calibrated->summary().empty());
}

TEST(RigCalibration, OutputStaysInsideTheWeightRange) {
  const RigMapping rig = facsRig(kNames);
  const float smileRef = referenceReach("AU12_LipCornerPuller_L");
  auto calibrated = calibrateRig(rig, std::vector<float>{smileRef * 0.5f, 0.1f, 0.1f, 0.1f});
  ASSERT_TRUE(calibrated);
  std::vector<float> au(actionUnits().size(), 0.0f), targets(4, 0.0f);
  au[*actionUnitIndex("AU12_LipCornerPuller_L")] = 1.0f;
  ASSERT_TRUE(calibrated->rig.apply(au, targets));
  EXPECT_FLOAT_EQ(targets[0], 1.0f) << "raised, but never driven past the rig's maximum (no extrapolation)";
  au[*actionUnitIndex("AU12_LipCornerPuller_L")] = 0.0f;
  ASSERT_TRUE(calibrated->rig.apply(au, targets));
  EXPECT_FLOAT_EQ(targets[0], 0.0f) << "intensity 0 is still neutral";
}

TEST(RigCalibration, OverridesMultiplyTheMeasuredScale) {
  const RigMapping rig = facsRig(kNames);
  const float jawRef = referenceReach("AU26_JawDrop");
  RigCalibrationOptions options;
  options.overrides = {{"AU26_JawDrop", 0.5f}};
  auto calibrated = calibrateRig(rig, std::vector<float>{0.1f, jawRef, 0.1f, 0.1f}, options);
  ASSERT_TRUE(calibrated);
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU26_JawDrop"), 0.5f);
}

// A rigged file's own scales (a face rigged by facial autorig states the
// built-in head's) stand for the measured ones; overrides still multiply.
TEST(RigCalibration, ScalesAFileStatesReplaceTheMeasuredOnes) {
  const RigMapping rig = facsRig(kNames);
  const float smileRef = referenceReach("AU12_LipCornerPuller_L");
  RigCalibrationOptions options;
  options.given = {{"AU12_LipCornerPuller_L", 0.93f}, {"AU26_JawDrop", 1.69f}};
  options.overrides = {{"AU26_JawDrop", 0.5f}};
  // Measured, the smile would stay (its reach is the reference) and the jaw be raised to 1.6.
  auto calibrated = calibrateRig(rig, std::vector<float>{smileRef, 0.01f, 0.1f, 0.1f}, options);
  ASSERT_TRUE(calibrated) << calibrated.error().message;
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU12_LipCornerPuller_L"), 0.93f);
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU26_JawDrop"), 1.69f * 0.5f);
}

TEST(RigCalibrationValidity, ScalesAFileStatesForNoChannelOrAsNoNumberAreNotedAndLeftOut) {
  const RigMapping rig = facsRig(kNames);
  const float smileRef = referenceReach("AU12_LipCornerPuller_L");
  RigCalibrationOptions options;
  options.given = {{"AU99_Nothing", 1.2f}, {"AU12_LipCornerPuller_L", NAN}, {"AU4_BrowLowerer", -1.0f}};
  auto calibrated = calibrateRig(rig, std::vector<float>{smileRef, 0.1f, 0.1f, 0.1f}, options);
  ASSERT_TRUE(calibrated) << calibrated.error().message;  // the file still loads
  EXPECT_FLOAT_EQ(gainOf(calibrated->rig, "AU12_LipCornerPuller_L"), 1.0f);  // measured
  const std::vector<std::string>& notes = calibrated->rig.report().notes;
  const auto noted = std::find_if(notes.begin(), notes.end(), [](const std::string& n) { return n.find("AU99_Nothing") != std::string::npos; });
  ASSERT_NE(noted, notes.end());
  EXPECT_NE(noted->find("3 entries"), std::string::npos) << *noted;
}

TEST(RigCalibration, UnmovedTargetsAreLeftAlone) {
  const RigMapping rig = facsRig(kNames);
  auto calibrated = calibrateRig(rig, std::vector<float>(4, 0.0f));
  ASSERT_TRUE(calibrated);
  for (const std::string& name : kNames) EXPECT_FLOAT_EQ(gainOf(calibrated->rig, name), 1.0f) << name;
}

}  // namespace
}  // namespace facial

namespace facial {
namespace {

std::filesystem::path writeRigMap(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = testing_support::freshTempDir("rig_calibration_" + name);
  const std::filesystem::path file = dir / (name + ".json");
  testing_support::writeFile(file, text);
  return file;
}

TEST(RigMapCalibrationValidity, UnknownChannelAndOutOfRangeScaleAreNamed) {
  const auto bad = loadRigMapFile(writeRigMap("bad", R"({"version": 1, "calibration": {"AU99": 1.2}})"), kNames);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("/calibration/AU99"), std::string::npos) << bad.error().message;
  const auto big = loadRigMapFile(
      writeRigMap("big", R"({"version": 1, "calibration": {"AU26_JawDrop": 9}})"), kNames);
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("outside [0, 4]"), std::string::npos) << big.error().message;
}

TEST(RigMapCalibration, CalibrationOnlyFileTunesTheDetectedScheme) {
  const std::filesystem::path file =
      writeRigMap("face", R"({"version": 1, "calibration": {"AU26_JawDrop": 0.8}})");
  auto parsed = loadRigMapFile(file, kNames);
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_FALSE(parsed->mapping);
  ASSERT_EQ(parsed->calibration.size(), 1u);
  EXPECT_EQ(parsed->calibration[0].first, "AU26_JawDrop");
  EXPECT_FLOAT_EQ(parsed->calibration[0].second, 0.8f);
  auto rig = buildRigMapping(kNames, RigMappingOptions{"face", {}, file});
  ASSERT_TRUE(rig) << rig.error().message;
  EXPECT_EQ(rig->scheme(), RigScheme::ActionUnits) << "no map in the file: detection";
  EXPECT_EQ(rigMapFileFor(RigMappingOptions{"face", {}, file}), file);
  EXPECT_FALSE(loadRigMap(file, kNames)) << "as a mapping, the file has none";
}

}  // namespace
}  // namespace facial
