#pragma once
// Image comparison for rendering tests: golden images in tests/goldens/,
// compared with a tolerance that absorbs rasteriser differences (llvmpipe
// versions, GPUs): a pixel "differs" when any channel is off by more than
// channelThreshold, and the test fails when more than maxDifferingFraction
// of the pixels differ (or the sizes differ).
//
// Regenerate: FACIAL_UPDATE_GOLDENS=1 writes the actual image as the new
// golden instead of comparing. On a mismatch, <build>/test-tmp/goldens/ gets
// NAME.actual.png and NAME.diff.png (differing pixels in red) to look at.
//
// Tests using these helpers link eng_scene (PNG reading and writing).
#include <cstddef>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/model.h"

namespace testing_support {

struct ImageTolerance {
  int channelThreshold = 16;            // 0..255, per channel
  double maxDifferingFraction = 0.005;  // of all pixels
};

struct ImageDifference {
  bool sameSize = false;
  size_t differingPixels = 0;
  double differingFraction = 0.0;
  int maxChannelDelta = 0;
};

ImageDifference compareImages(const eng::Image& expected, const eng::Image& actual, int channelThreshold);

// Red where the images differ beyond the threshold, dimmed expected image elsewhere.
eng::Image differenceImage(const eng::Image& expected, const eng::Image& actual, int channelThreshold);

bool updateGoldensRequested();  // FACIAL_UPDATE_GOLDENS=1
std::filesystem::path goldenPath(const std::string& name);  // tests/goldens/NAME.png

// EXPECT_TRUE(matchesGolden(image, "facecap_smile"));
::testing::AssertionResult matchesGolden(const eng::Image& actual, const std::string& name,
                                         const ImageTolerance& tolerance = {});

}  // namespace testing_support
