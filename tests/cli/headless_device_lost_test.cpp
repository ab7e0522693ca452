// A Vulkan device lost during a headless run (injected with
// FACIAL_VK_FAULTS=device-lost@N: lavapipe never loses one): every command that
// renders offscreen stops with ONE line naming the command and the problem,
// exits with status 1 (not a crash), and leaves no half-written output file
// behind.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/image_io.h"
#include "tests/cli/cli_runner.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

namespace fs = std::filesystem;

// The lines of `err` that start with "facial COMMAND: error:".
std::vector<std::string> errorLines(const std::string& err, const std::string& command) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("facial " + command + ": error:", 0) == 0) lines.push_back(line);
  return lines;
}

// Ran `command` with the device lost at the `submission`-th frame: non-zero
// exit, the seam announced, one error line that says the device was lost.
void expectLostDeviceReported(const std::string& command, const std::vector<std::string>& args, int submission) {
  const std::string faults = "device-lost@" + std::to_string(submission);
  const CommandOutput run = runFacial(args, {"FACIAL_VK_FAULTS=" + faults});
  // 1, as for any error; -1 is a signal: the injected loss leaves the frame
  // really in flight, and a teardown that freed its buffers under it crashed
  // lavapipe's threads after the error line.
  EXPECT_EQ(run.exitCode, 1) << command << ":\n" << run.err;
  EXPECT_NE(run.err.find("injecting faults for a test: FACIAL_VK_FAULTS=" + faults), std::string::npos) << run.err;
  const std::vector<std::string> lines = errorLines(run.err, command);
  ASSERT_EQ(lines.size(), 1u) << command << ":\n" << run.err;
  EXPECT_NE(lines[0].find("the Vulkan device was lost (vkQueueSubmit failed: VK_ERROR_DEVICE_LOST): its driver "
                          "reset or failed, or the GPU was removed; nothing more can be drawn"),
            std::string::npos)
      << lines[0];
}

class HeadlessDeviceLost : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing_support::freshTempDir("headless_device_lost");
    face_ = writeTestFace("headless_device_lost_face");
  }
  fs::path dir_;
  fs::path face_;
};

TEST_F(HeadlessDeviceLost, RenderWritesNoImage) {
  const fs::path out = dir_ / "render.png";
  expectLostDeviceReported("render", {"render", face_.string(), "--size", "64x64", "--out", out.string()}, 1);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(HeadlessDeviceLost, ExpressWritesNoImage) {
  const fs::path out = dir_ / "express.png";
  expectLostDeviceReported(
      "express", {"express", "happy", "--model", face_.string(), "--size", "64x64", "--out", out.string()}, 1);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(HeadlessDeviceLost, SheetStopsAtTheLostTileAndWritesNoSheet) {
  const fs::path out = dir_ / "sheet.png";
  expectLostDeviceReported("sheet", {"sheet", "--model", face_.string(), "--size", "48", "--out", out.string()}, 3);
  EXPECT_FALSE(fs::exists(out));
}

// The tour stops at frame 2: frame folders are written whole (issue 37), so
// the two frames rendered before it are dropped with their staging folder;
// the GIF and the contact sheet do not exist, and no partial file is left.
TEST_F(HeadlessDeviceLost, DemoTourLeavesNoGifOrSheet) {
  const fs::path out = dir_ / "tour";
  expectLostDeviceReported("demo",
                           {"demo", "--headless", "--size", "64x64", "--fps", "10", "--seconds", "0.6", "--out",
                            out.string()},
                           3);
  EXPECT_FALSE(fs::exists(out / "tour.gif"));
  EXPECT_FALSE(fs::exists(out / "contact_sheet.png"));
  if (fs::exists(out)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(out))
      EXPECT_FALSE(entry.is_regular_file()) << "left behind: " << entry.path();
  }
}

}  // namespace
}  // namespace cli_test
