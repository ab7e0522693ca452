#include "tests/common/golden.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"

namespace testing_support {

ImageDifference compareImages(const eng::Image& expected, const eng::Image& actual, int channelThreshold) {
  ImageDifference d;
  d.sameSize = expected.width == actual.width && expected.height == actual.height &&
               expected.rgba8.size() == actual.rgba8.size();
  if (!d.sameSize) return d;
  const size_t pixels = expected.rgba8.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (size_t c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(int(expected.rgba8[p * 4 + c]) - int(actual.rgba8[p * 4 + c])));
    d.maxChannelDelta = std::max(d.maxChannelDelta, worst);
    if (worst > channelThreshold) ++d.differingPixels;
  }
  d.differingFraction = pixels ? double(d.differingPixels) / double(pixels) : 0.0;
  return d;
}

eng::Image differenceImage(const eng::Image& expected, const eng::Image& actual, int channelThreshold) {
  eng::Image out = expected;
  out.name = "difference";
  if (expected.rgba8.size() != actual.rgba8.size()) return out;
  for (size_t p = 0; p < out.rgba8.size() / 4; ++p) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(expected.rgba8[p * 4 + c]) - int(actual.rgba8[p * 4 + c])));
    uint8_t* px = &out.rgba8[p * 4];
    if (worst > channelThreshold) {
      px[0] = 255, px[1] = 0, px[2] = 0;
    } else {
      for (size_t c = 0; c < 3; ++c) px[c] = static_cast<uint8_t>(px[c] / 3);
    }
    px[3] = 255;
  }
  return out;
}

bool updateGoldensRequested() {
  const char* v = std::getenv("FACIAL_UPDATE_GOLDENS");
  return v && std::strcmp(v, "1") == 0;
}

std::filesystem::path goldenPath(const std::string& name) { return sourceDir() / "tests" / "goldens" / (name + ".png"); }

::testing::AssertionResult matchesGolden(const eng::Image& actual, const std::string& name,
                                         const ImageTolerance& tolerance) {
  const std::filesystem::path golden = goldenPath(name);
  if (updateGoldensRequested()) {
    std::filesystem::create_directories(golden.parent_path());
    if (auto written = eng::writePng(golden, actual.width, actual.height, actual.rgba8); !written)
      return ::testing::AssertionFailure() << "cannot update golden: " << written.error().message;
    return ::testing::AssertionSuccess() << "updated " << golden.string();
  }
  auto expected = eng::readImage(golden);
  if (!expected)
    return ::testing::AssertionFailure() << "golden " << golden.string() << " unreadable (" << expected.error().message
                                         << "); create it with FACIAL_UPDATE_GOLDENS=1";
  const ImageDifference d = compareImages(*expected, actual, tolerance.channelThreshold);
  if (d.sameSize && d.differingFraction <= tolerance.maxDifferingFraction)
    return ::testing::AssertionSuccess() << name << ": " << d.differingPixels << " pixels differ";

  const std::filesystem::path outDir = binaryDir() / "test-tmp" / "goldens";
  const std::filesystem::path actualPath = outDir / (name + ".actual.png");
  const std::filesystem::path diffPath = outDir / (name + ".diff.png");
  // Names may carry folders ("sheets/head_basic"): create the one the files go in.
  std::filesystem::create_directories(actualPath.parent_path());
  (void)eng::writePng(actualPath, actual.width, actual.height, actual.rgba8);
  auto failure = ::testing::AssertionFailure();
  if (!d.sameSize) {
    return failure << name << ": size " << actual.width << "x" << actual.height << " differs from the golden's "
                   << expected->width << "x" << expected->height << " (actual image: " << actualPath.string() << ")";
  }
  const eng::Image diff = differenceImage(*expected, actual, tolerance.channelThreshold);
  (void)eng::writePng(diffPath, diff.width, diff.height, diff.rgba8);
  return failure << name << ": " << d.differingPixels << " pixels (" << d.differingFraction * 100.0
                 << "%) differ by more than " << tolerance.channelThreshold << " (max delta " << d.maxChannelDelta
                 << "), allowed " << tolerance.maxDifferingFraction * 100.0 << "%; see " << actualPath.string()
                 << " and " << diffPath.string();
}

}  // namespace testing_support
