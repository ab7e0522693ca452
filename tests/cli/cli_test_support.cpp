#include "tests/cli/cli_test_support.h"

#include <cstdlib>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"

namespace cli_test {

::testing::AssertionResult ranCleanly(const CommandOutput& run) {
  if (run.exitCode != 0)
    return ::testing::AssertionFailure() << "exit code " << run.exitCode << "; stderr:\n" << run.err;
  if (run.err.find("validation on") == std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation was not active; stderr:\n" << run.err;
  if (run.err.find("vulkan validation:") != std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation messages; stderr:\n" << run.err;
  return ::testing::AssertionSuccess();
}

eng::Image readPngOrFail(const std::filesystem::path& path) {
  auto image = eng::readImage(path);
  if (!image) {
    ADD_FAILURE() << image.error().message;
    return {};
  }
  return std::move(image).value();
}

std::filesystem::path facecapPath() { return testing_support::sharedDir() / "assets" / "facecap.glb"; }

double differingFraction(const eng::Image& a, const eng::Image& b, int threshold) {
  if (a.width != b.width || a.height != b.height || a.rgba8.empty()) return 1.0;
  size_t differing = 0;
  for (size_t p = 0; p < a.rgba8.size(); p += 4)
    for (size_t c = 0; c < 3; ++c)
      if (std::abs(int(a.rgba8[p + c]) - int(b.rgba8[p + c])) > threshold) {
        ++differing;
        break;
      }
  return double(differing) / double(a.rgba8.size() / 4);
}

}  // namespace cli_test
