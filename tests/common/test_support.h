#pragma once
// Shared helpers for the test executables.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace testing_support {

// ../shared beside the project; empty path when it is absent.
std::filesystem::path sharedDir();
// Skips the current test (with a message saying why) when ../shared is absent.
#define FACIAL_REQUIRE_SHARED()                                                              \
  do {                                                                                       \
    if (::testing_support::sharedDir().empty())                                              \
      GTEST_SKIP() << "../shared is absent beside the project: third-party asset test skipped"; \
  } while (0)

// Every .gltf / .glb under ../shared's assets/ and compressed/ (the meshopt and
// Draco variants), sorted; empty when ../shared is absent.
std::vector<std::filesystem::path> sharedModelFiles();

std::filesystem::path sourceDir();
std::filesystem::path binaryDir();

// A fresh directory under the build tree for one test, removed first if present.
std::filesystem::path freshTempDir(const std::string& name);

void writeFile(const std::filesystem::path& path, const std::string& bytes);

// Files in `dir` (not below) whose name holds ".partial": what a whole-file
// write (eng::writeFileWhole, the GIF, WAV and video writers) left behind.
size_t partialFilesIn(const std::filesystem::path& dir);
// A whole file as a string ("" when it cannot be read).
std::string readTextFile(const std::filesystem::path& path);

}  // namespace testing_support
