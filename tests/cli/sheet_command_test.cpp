// `facial sheet`: labelled contact sheets of the basic and compound presets,
// all tiles from one Vulkan context, compared with goldens in
// tests/goldens/sheets/ (regenerate with FACIAL_UPDATE_GOLDENS=1).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/golden.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

// Small tiles keep the goldens small; `facial sheet` defaults to 256.
constexpr const char* kGoldenTileSize = "160";
constexpr int kGoldenTilePixels = 160 * 160;

class SheetCommand : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing_support::freshTempDir("sheet_command"); }

  // Runs `facial sheet` with `args` + --out; checks it ran cleanly with ONE
  // Vulkan context for every tile; returns the sheet.
  eng::Image sheet(std::vector<std::string> args, const std::string& name) {
    const std::filesystem::path out = dir_ / (name + ".png");
    args.insert(args.begin(), "sheet");
    args.insert(args.end(), {"--out", out.string()});
    const CommandOutput run = runFacial(args);
    EXPECT_TRUE(ranCleanly(run)) << name;
    EXPECT_EQ(countOccurrences(run.err, "vulkan: using"), 1u) << "one context for all tiles:\n" << run.err;
    EXPECT_NE(run.out.find("wrote " + out.string()), std::string::npos) << run.out;
    return readPngOrFail(out);
  }

  // The default tolerance is meant for one rendered image; a sheet holds
  // many, so the allowance is scaled to what it allows within ONE tile (a
  // single tile whose expression changed must fail).
  ::testing::AssertionResult matchesSheetGolden(const eng::Image& image, const std::string& name) {
    // The golden helper writes NAME.actual.png / NAME.diff.png but creates no sub-folders.
    std::filesystem::create_directories(testing_support::goldenPath("sheets/" + name).parent_path());
    std::filesystem::create_directories(testing_support::binaryDir() / "test-tmp" / "goldens" / "sheets");
    testing_support::ImageTolerance tolerance;
    if (image.width > 0 && image.height > 0)
      tolerance.maxDifferingFraction *= double(kGoldenTilePixels) / (double(image.width) * image.height);
    return testing_support::matchesGolden(image, "sheets/" + name, tolerance);
  }

  std::filesystem::path dir_;
};

TEST_F(SheetCommand, BasicSheetHasSevenLabelledTilesInTwoRows) {
  const std::filesystem::path face = writeTestFace("sheet_command_face");
  const eng::Image image = sheet({"--model", face.string(), "--size", "64"}, "test_face_basic");
  // 4 columns x 2 rows of 64 px tiles with 12 px padding, label bands and a title band.
  EXPECT_EQ(image.width, 4 * (64 + 12) + 12);
  EXPECT_GT(image.height, 2 * (64 + 12) + 12);
  EXPECT_LT(image.height, image.width);
}

TEST_F(SheetCommand, CompoundSheetHasOneTilePerCompoundPreset) {
  const std::filesystem::path face = writeTestFace("sheet_command_face");
  const eng::Image image = sheet({"--model", face.string(), "--size", "48", "--compound"}, "test_face_compound");
  EXPECT_EQ(image.width, 5 * (48 + 12) + 12) << "the 10 compounds in 5 columns";
}

TEST_F(SheetCommand, BuiltInHeadBasicMatchesGolden) {
  const eng::Image image = sheet({"--size", kGoldenTileSize}, "head_basic");  // default model: data/head.glb
  EXPECT_TRUE(matchesSheetGolden(image, "head_basic"));
}

TEST_F(SheetCommand, BuiltInHeadCompoundMatchesGolden) {
  const eng::Image image = sheet({"--size", kGoldenTileSize, "--compound"}, "head_compound");
  EXPECT_TRUE(matchesSheetGolden(image, "head_compound"));
}

TEST_F(SheetCommand, FacecapBasicMatchesGolden) {
  FACIAL_REQUIRE_SHARED();
  const eng::Image image = sheet({"--model", facecapPath().string(), "--size", kGoldenTileSize}, "facecap_basic");
  EXPECT_TRUE(matchesSheetGolden(image, "facecap_basic"));
}

TEST_F(SheetCommand, FacecapCompoundMatchesGolden) {
  FACIAL_REQUIRE_SHARED();
  const eng::Image image =
      sheet({"--model", facecapPath().string(), "--size", kGoldenTileSize, "--compound"}, "facecap_compound");
  EXPECT_TRUE(matchesSheetGolden(image, "facecap_compound"));
}

// ---- refused input ----

using SheetCommandValidity = SheetCommand;
TEST_F(SheetCommandValidity, MissingModelFileIsNamed) {
  const std::string missing = (dir_ / "no_such_face.glb").string();
  const CommandOutput run = runFacial({"sheet", "--model", missing, "--out", (dir_ / "x.png").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("facial sheet: error: " + missing), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

TEST_F(SheetCommandValidity, TileSizeOutOfRangeAndNanIntensityAreRefused) {
  const std::filesystem::path face = writeTestFace("sheet_command_face");
  const CommandOutput tiny = runFacial({"sheet", "--model", face.string(), "--size", "4", "--out", "x.png"});
  EXPECT_NE(tiny.exitCode, 0);
  EXPECT_NE(tiny.err.find("--size"), std::string::npos) << tiny.err;
  const CommandOutput nan =
      runFacial({"sheet", "--model", face.string(), "--intensity", "nan", "--out", (dir_ / "x.png").string()});
  EXPECT_NE(nan.exitCode, 0);
  EXPECT_NE(nan.err.find("--intensity"), std::string::npos) << nan.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace cli_test
