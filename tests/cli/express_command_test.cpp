// `facial express`: a preset rendered through the model's rig mapping, with
// validation on; refused input exits non-zero with one line naming the problem.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

class ExpressCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing_support::freshTempDir("express_command");
    face_ = writeTestFace("express_command_face");
  }
  // Renders `expression` on the test face at 96x64; returns the image.
  eng::Image express(const std::string& expression, const std::string& intensity) {
    const std::filesystem::path out = dir_ / (expression + "_" + intensity + ".png");
    const CommandOutput run = runFacial({"express", expression, "--intensity", intensity, "--model", face_.string(),
                                         "--size", "96x64", "--out", out.string()});
    EXPECT_TRUE(ranCleanly(run)) << expression;
    EXPECT_NE(run.out.find("wrote " + out.string()), std::string::npos) << run.out;
    return readPngOrFail(out);
  }
  std::filesystem::path dir_;
  std::filesystem::path face_;
};

size_t differingPixels(const eng::Image& a, const eng::Image& b, int x0, int x1, int y0, int y1) {
  size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c)
        if (a.rgba8[(size_t(y) * a.width + x) * 4 + c] != b.rgba8[(size_t(y) * b.width + x) * 4 + c]) {
          ++n;
          break;
        }
  return n;
}

TEST_F(ExpressCommand, PresetMovesItsDrivenTargetsOnly) {
  const eng::Image neutral = express("neutral", "1");
  const eng::Image happy = express("happy", "1");
  ASSERT_EQ(neutral.width, 96);
  ASSERT_EQ(neutral.height, 64);
  ASSERT_EQ(happy.rgba8.size(), neutral.rgba8.size());
  // The smile targets bulge the sheet's lower half toward the camera; the
  // brow target (default 0.3, driven to 0 by both presets) is the same.
  EXPECT_GT(differingPixels(neutral, happy, 0, 96, 32, 64), 100u);
  EXPECT_EQ(differingPixels(neutral, happy, 0, 96, 0, 20), 0u);
}

TEST_F(ExpressCommand, IntensityZeroIsNeutralAndAboveOneIsClamped) {
  const eng::Image neutral = express("neutral", "1");
  EXPECT_EQ(express("happy", "0").rgba8, neutral.rgba8);
  EXPECT_EQ(express("happy", "0.5").rgba8 == neutral.rgba8, false);

  const std::filesystem::path out = dir_ / "clamped.png";
  const CommandOutput run = runFacial({"express", "happy", "--intensity", "3", "--model", face_.string(), "--size",
                                       "96x64", "--out", out.string()});
  EXPECT_TRUE(ranCleanly(run));
  EXPECT_NE(run.err.find("intensity 3 clamped to [0, 1]"), std::string::npos) << run.err;
  EXPECT_EQ(readPngOrFail(out).rgba8, express("happy", "1").rgba8);
}

TEST_F(ExpressCommand, FacecapSmilesThroughTheArkitMapping) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path out = dir_ / "facecap_happy.png";
  const CommandOutput run = runFacial({"express", "happy", "--model", facecapPath().string(), "--size", "128x128",
                                       "--yaw", "20", "--pitch", "5", "--out", out.string()});
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_NE(run.out.find("facecap 'happy' at 1"), std::string::npos) << run.out;
  const eng::Image image = readPngOrFail(out);
  EXPECT_EQ(image.width, 128);
  EXPECT_EQ(image.height, 128);
}

// ---- refused input ----

using ExpressCommandValidity = ExpressCommand;
TEST_F(ExpressCommandValidity, UnknownExpressionListsTheAvailableOnes) {
  const CommandOutput run =
      runFacial({"express", "elation", "--model", face_.string(), "--out", (dir_ / "x.png").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("facial express: error: unknown expression 'elation'; available: neutral, happy, sad, "
                         "surprise, fear, anger, disgust"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png"));
}

TEST_F(ExpressCommandValidity, NonNumericOrNanIntensityIsRefused) {
  for (const char* bad : {"nan", "NaN", "inf", "abc", ""}) {
    const CommandOutput run = runFacial(
        {"express", "happy", "--intensity", bad, "--model", face_.string(), "--out", (dir_ / "x.png").string()});
    EXPECT_NE(run.exitCode, 0) << bad;
    EXPECT_NE(run.err.find("intensity"), std::string::npos) << bad << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "x.png")) << bad;
  }
}

TEST_F(ExpressCommandValidity, MissingModelFileIsNamed) {
  const std::string missing = (dir_ / "no_such_face.glb").string();
  const CommandOutput run = runFacial({"express", "happy", "--model", missing, "--out", (dir_ / "x.png").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("facial express: error: " + missing), std::string::npos) << run.err;
}

TEST_F(ExpressCommandValidity, MissingBuiltInHeadIsNamed) {
  const std::filesystem::path emptyData = testing_support::freshTempDir("express_empty_data");
  const CommandOutput run =
      runFacial({"express", "happy", "--out", (dir_ / "x.png").string()}, {"FACIAL_DATA_DIR=" + emptyData.string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find((emptyData / "head.glb").string()), std::string::npos) << run.err;
}

TEST_F(ExpressCommandValidity, BadSizeAndMissingOutputAreRefused) {
  const CommandOutput badSize =
      runFacial({"express", "happy", "--model", face_.string(), "--size", "64", "--out", (dir_ / "x.png").string()});
  EXPECT_NE(badSize.exitCode, 0);
  EXPECT_NE(badSize.err.find("--size '64' is not WxH"), std::string::npos) << badSize.err;

  const CommandOutput noOut = runFacial({"express", "happy", "--model", face_.string()});
  EXPECT_NE(noOut.exitCode, 0);
  EXPECT_NE(noOut.err.find("--out"), std::string::npos) << noOut.err;

  const std::string unwritable = (dir_ / "missing_folder" / "x.png").string();
  const CommandOutput badOut =
      runFacial({"express", "happy", "--model", face_.string(), "--size", "32x32", "--out", unwritable});
  EXPECT_NE(badOut.exitCode, 0);
  EXPECT_NE(badOut.err.find(unwritable), std::string::npos) << badOut.err;
}

}  // namespace
}  // namespace cli_test
