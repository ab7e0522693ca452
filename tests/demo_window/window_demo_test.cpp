// `facial demo` with a display: runs the built program under a virtual X
// server (xvfb-run), presses keys with xdotool, and checks the screenshot it
// writes on its last frame (--quit-after, --screenshot).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

bool onPath(const char* program) {
  return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0;
}

#define REQUIRE_VIRTUAL_DISPLAY()                                                                   \
  do {                                                                                              \
    if (!onPath("xvfb-run") || !onPath("xdotool"))                                                  \
      GTEST_SKIP() << "xvfb-run or xdotool is not installed: the window demo cannot run headless"; \
  } while (0)

struct DemoRun {
  int exitCode = -1;
  std::string log;  // stdout + stderr of the demo
  fs::path screenshot;
};

// Runs `facial demo --quit-after <seconds> --screenshot <dir>/shot.png` under
// xvfb-run with validation on; `keys` (xdotool key names) are pressed once
// the window is up and focused.
DemoRun runDemo(const fs::path& dir, float seconds, const std::string& keys) {
  DemoRun run;
  run.screenshot = dir / "shot.png";
  const fs::path log = dir / "demo.log";
  const fs::path program = fs::path(FACIAL_BINARY_DIR) / "bin" / "facial";
  std::ostringstream script;
  script << "FACIAL_VALIDATION=1 '" << program.string() << "' demo --quit-after " << seconds << " --screenshot '"
         << run.screenshot.string() << "' >'" << log.string() << "' 2>&1 & pid=$!; ";
  if (!keys.empty())
    script << "timeout 30 xdotool search --sync --name 'facial demo' windowfocus --sync key --delay 100 " << keys
           << " >/dev/null 2>&1; ";
  script << "wait $pid";
  const std::string command =
      "xvfb-run -a -s '-screen 0 1280x800x24' sh -c \"" + script.str() + "\"";
  const int status = std::system(command.c_str());
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.log = text.str();
  return run;
}

// Exit 0, validation active and silent, a 1280x800 screenshot.
::testing::AssertionResult ranCleanly(const DemoRun& run, eng::Image& shot) {
  if (run.exitCode != 0) return ::testing::AssertionFailure() << "exit code " << run.exitCode << ":\n" << run.log;
  if (run.log.find("validation on") == std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation was not active:\n" << run.log;
  if (run.log.find("vulkan validation:") != std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation messages:\n" << run.log;
  auto image = eng::readImage(run.screenshot);
  if (!image) return ::testing::AssertionFailure() << image.error().message << "\n" << run.log;
  shot = std::move(*image);
  if (shot.width != 1280 || shot.height != 800)
    return ::testing::AssertionFailure() << "screenshot is " << shot.width << "x" << shot.height << ", not 1280x800";
  return ::testing::AssertionSuccess();
}

int channelDistance(const eng::Image& a, size_t ia, const eng::Image& b, size_t ib) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d += std::abs(int(a.rgba8[ia + c]) - int(b.rgba8[ib + c]));
  return d;
}

// Pixels of the right two thirds (the face, clear of the panel) that differ
// from the backdrop's top-right corner colour.
double facePixelFraction(const eng::Image& shot) {
  const size_t corner = (size_t(2) * shot.width + shot.width - 3) * 4;
  size_t face = 0, total = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = shot.width / 3; x < shot.width; ++x, ++total)
      if (channelDistance(shot, (size_t(y) * shot.width + x) * 4, shot, corner) > 60) ++face;
  return double(face) / double(total);
}

// Mean per-pixel colour distance over the right two thirds of the frame.
double meanDifference(const eng::Image& a, const eng::Image& b) {
  double sum = 0;
  size_t total = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = a.width / 3; x < a.width; ++x, ++total) {
      const size_t i = (size_t(y) * a.width + x) * 4;
      sum += channelDistance(a, i, b, i);
    }
  return sum / double(total);
}

TEST(WindowDemo, KeyTwoTurnsTheFaceHappyAndTheLastFrameIsSaved) {
  REQUIRE_VIRTUAL_DISPLAY();
  ASSERT_TRUE(fs::exists(testing_support::sourceDir() / "data" / "head.glb"))
      << "data/head.glb (the built-in head) is missing: run facial make-head --out data/head.glb";

  const DemoRun neutral = runDemo(testing_support::freshTempDir("demo_window_neutral"), 4.0f, "");
  eng::Image neutralShot;
  ASSERT_TRUE(ranCleanly(neutral, neutralShot));
  EXPECT_NE(neutral.log.find("final state neutral"), std::string::npos) << neutral.log;
  EXPECT_GT(facePixelFraction(neutralShot), 0.05) << "the face covers part of the frame";

  const DemoRun happy = runDemo(testing_support::freshTempDir("demo_window_happy"), 6.0f, "2");
  eng::Image happyShot;
  ASSERT_TRUE(ranCleanly(happy, happyShot));
  EXPECT_NE(happy.log.find("final state happy"), std::string::npos) << "key 2 triggers happy:\n" << happy.log;
  EXPECT_GT(facePixelFraction(happyShot), 0.05) << "the face covers part of the frame";
  EXPECT_GT(meanDifference(neutralShot, happyShot), 1.0) << "the happy face differs from the neutral one";
}

}  // namespace
