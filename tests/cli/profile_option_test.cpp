// --profile: `facial play` ends with one line per stage it measured (mean
// ms per frame and share of the frame), the GPU passes where the device has
// timestamps; without the flag none of them.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test::profile_option {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTimeline =
    R"({"version": 1, "duration": 1, "tracks": [{"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})";

TEST(ProfileOption, PlayPrintsWhereEachFramesTimeWent) {
  const fs::path dir = testing_support::freshTempDir("profile_option_play");
  const fs::path face = writeTestFace("profile_option_face");
  testing_support::writeFile(dir / "t.json", kTimeline);
  std::vector<std::string> args{"play", (dir / "t.json").string(), "--model", face.string(), "--fps", "8",
                                "--seconds", "1", "--size", "32x32", "--out", (dir / "frames").string()};
  const CommandOutput plain = runFacial(args);
  ASSERT_TRUE(ranCleanly(plain)) << plain.err;
  EXPECT_EQ(plain.out.find("profile play"), std::string::npos) << plain.out;

  args.push_back("--profile");
  const CommandOutput run = runFacial(args);
  ASSERT_TRUE(ranCleanly(run)) << run.err;
  EXPECT_NE(run.out.find("profile play: 8 frames, "), std::string::npos) << run.out;
  for (const char* stage : {"step (graph, speech, materials)", "submit (upload, record)", "wait for the GPU",
                            "read-back", "PNG encoding", "GPU: morph + shadow map", "GPU: 3D view + resolve + copy"})
    EXPECT_NE(run.out.find(std::string("  ") + stage + " "), std::string::npos) << stage << " in\n" << run.out;
  EXPECT_NE(run.out.find(" %\n"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace cli_test::profile_option
