// The demo's headless path end to end: the binary plays the tour on lavapipe
// (validation on) and writes frames, a GIF and a contact sheet; the sheet is
// compared with a reviewed golden. Regenerate with FACIAL_UPDATE_GOLDENS=1.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/image_io.h"
#include "tests/common/golden.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int exitCode = -1;
  std::string output;
};

CommandResult run(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string facialBinary() { return (testing_support::binaryDir() / "bin" / "facial").string(); }

TEST(HeadlessDemoTest, TourWritesFramesAnimationAndContactSheet) {
  const fs::path out = testing_support::freshTempDir("headless_demo");
  // Small frames and a low rate keep this quick on 2 cores; the tour is the full one.
  const CommandResult r = run("env -u DISPLAY -u WAYLAND_DISPLAY FACIAL_VALIDATION=1 " + facialBinary() +
                              " demo --size 160x160 --fps 4 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // The layer really was on, and said nothing (its messages start "vulkan validation:").
  EXPECT_NE(r.output.find("validation on"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vulkan validation:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("playing the tour headless into " + out.string()), std::string::npos) << r.output;

  size_t frames = 0;
  for (const auto& entry : fs::directory_iterator(out / "frames")) frames += entry.path().extension() == ".png";
  // One pass: 7 states x 2.4 s exit time (blend included) + 0.8 s back to neutral + 0.5 s settle, at 4 fps.
  EXPECT_EQ(frames, 73u);
  ASSERT_TRUE(fs::exists(out / "tour.gif"));
  EXPECT_GT(fs::file_size(out / "tour.gif"), 10000u);

  auto sheet = eng::readImage(out / "contact_sheet.png");
  ASSERT_TRUE(sheet.ok()) << sheet.error().message;
  EXPECT_NE(r.output.find("(7 states)"), std::string::npos) << r.output;
  EXPECT_TRUE(testing_support::matchesGolden(*sheet, "demo/tour_contact_sheet"));
}

TEST(HeadlessDemoTest, MissingModelIsAClearError) {
  const fs::path out = testing_support::freshTempDir("headless_demo_missing");
  const CommandResult r = run("env -u DISPLAY " + facialBinary() + " demo --headless --model " +
                              (out / "nope.glb").string() + " --out " + out.string());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("nope.glb"), std::string::npos) << r.output;
}

TEST(HeadlessDemoTest, CrowdRendersManyFacesInOneRun) {
  const fs::path out = testing_support::freshTempDir("headless_demo_crowd");
  const CommandResult r = run("env -u DISPLAY FACIAL_VALIDATION=1 " + facialBinary() +
                              " demo --headless --crowd 9 --size 192x192 --fps 4 --seconds 3 --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("9 faces"), std::string::npos) << r.output;
  auto last = eng::readImage(out / "frames" / "frame_0011.png");
  ASSERT_TRUE(last.ok()) << last.error().message;
}

}  // namespace
