#pragma once
// Helpers shared by the CLI command tests.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/model.h"
#include "tests/cli/cli_runner.h"

namespace cli_test {

// Succeeded with validation active and silent: exit 0, the Vulkan context
// said "validation on", and no validation message was logged.
::testing::AssertionResult ranCleanly(const CommandOutput& run);

// The PNG at `path`, or an empty image after a test failure naming it.
eng::Image readPngOrFail(const std::filesystem::path& path);

std::filesystem::path facecapPath();

// Fraction of the pixels whose RGB differs by more than `threshold` in some
// channel (1 when the sizes differ or the images are empty).
double differingFraction(const eng::Image& a, const eng::Image& b, int threshold = 16);

}  // namespace cli_test
