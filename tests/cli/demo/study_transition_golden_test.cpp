// The study's transition, neutral -> happy -> angry, played by `facial play`
// from data/graphs/study_transition.json (cosine-eased state-machine
// transitions) on lavapipe. Every frame of the run goes into one labelled
// strip compared with a reviewed golden, so a change in the easing, the state
// machine's timing, the presets or the rendering shows up as a changed frame.
// Regenerate with FACIAL_UPDATE_GOLDENS=1.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/image/contact_sheet.h"
#include "engine/scene/image_io.h"
#include "tests/common/golden.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 18;  // 4.5 s at 4 fps
constexpr float kFps = 4.0f;

std::string runPlay(const fs::path& out, int& exitCode) {
  const std::string command = "env -u DISPLAY FACIAL_VALIDATION=1 " +
                              (testing_support::binaryDir() / "bin" / "facial").string() + " play " +
                              (testing_support::sourceDir() / "data" / "graphs" / "study_transition.json").string() +
                              " --fps 4 --seconds 4.5 --size 128x128 --out " + out.string() + " 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return output;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int status = pclose(pipe);
  exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

// Mean absolute channel difference between two frames of one size.
double meanDifference(const eng::Image& a, const eng::Image& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) sum += std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
  return sum / double(a.rgba8.size());
}

TEST(StudyTransition, NeutralToHappyToAngryFramesMatchTheGolden) {
  const fs::path out = testing_support::freshTempDir("study_transition");
  int exitCode = -1;
  const std::string output = runPlay(out, exitCode);
  ASSERT_EQ(exitCode, 0) << output;
  EXPECT_NE(output.find("validation on"), std::string::npos) << output;
  EXPECT_EQ(output.find("vulkan validation:"), std::string::npos) << output;

  std::vector<eng::Image> frames;
  std::vector<eng::ContactSheetTile> tiles;
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", i);
    auto frame = eng::readImage(out / name);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    eng::ContactSheetTile tile{eng::Canvas(frame->width, frame->height), ""};
    tile.image.rgba = frame->rgba8;
    char label[32];
    std::snprintf(label, sizeof label, "%.2f s", i / kFps);
    tile.label = label;
    tiles.push_back(std::move(tile));
    frames.push_back(std::move(*frame));
  }

  // The face holds still while a state holds and moves while a transition runs:
  // neutral until 0.5 s, happy from 1.5 s, anger after its own exit time.
  // Per-step change of the picture: zero while a state holds; during a
  // cosine-eased transition small at both ends and largest in the middle.
  std::vector<double> step(kFrames - 1);
  for (int i = 0; i + 1 < kFrames; ++i) step[i] = meanDifference(frames[i], frames[i + 1]);
  for (int i : {0, 1, 6, 7, 12, 13, 14, 15, 16}) EXPECT_LT(step[i], 0.01) << "a state holds at frame " << i;
  // neutral -> happy over 0.5..1.5 s (frames 2..6), happy -> anger over 2.0..3.0 s (frames 8..12).
  EXPECT_GT(step[3], step[2]) << "cosine easing starts slowly";
  EXPECT_GT(step[4], step[5]) << "cosine easing ends slowly";
  EXPECT_GT(step[9], step[8]);
  EXPECT_GT(step[10], step[11]);
  EXPECT_GT(meanDifference(frames[0], frames[7]), 0.25) << "happy differs from neutral";
  EXPECT_GT(meanDifference(frames[7], frames[kFrames - 1]), 0.5) << "anger differs from happy";

  eng::ContactSheetOptions options;
  options.columns = 6;
  options.padding = 6;
  options.labelHeight = 16.0f;
  options.title = "neutral -> happy -> anger (cosine, 4 fps)";
  auto sheet = eng::composeContactSheet(tiles, options);
  ASSERT_TRUE(sheet.ok()) << sheet.error().message;
  eng::Image image;
  image.width = sheet->width;
  image.height = sheet->height;
  image.rgba8 = sheet->rgba;
  EXPECT_TRUE(testing_support::matchesGolden(image, "transitions/neutral_happy_anger"));
}

}  // namespace
