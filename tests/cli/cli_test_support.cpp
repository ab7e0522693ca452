#include "tests/cli/cli_test_support.h"

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

}  // namespace cli_test
