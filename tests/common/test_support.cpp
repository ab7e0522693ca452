#include "tests/common/test_support.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace testing_support {

std::filesystem::path sharedDir() {
  std::filesystem::path p = FACIAL_SHARED_DIR;
  std::error_code ec;
  return std::filesystem::is_directory(p / "assets", ec) ? p : std::filesystem::path{};
}

std::vector<std::filesystem::path> sharedModelFiles() {
  std::vector<std::filesystem::path> files;
  if (sharedDir().empty()) return files;
  for (const char* folder : {"assets", "compressed"}) {
    std::error_code ec;
    if (!std::filesystem::is_directory(sharedDir() / folder, ec)) continue;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(sharedDir() / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::filesystem::path sourceDir() { return FACIAL_SOURCE_DIR; }
std::filesystem::path binaryDir() { return FACIAL_BINARY_DIR; }

size_t partialFilesIn(const std::filesystem::path& dir) {
  size_t count = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.is_regular_file() && entry.path().filename().string().find(".partial") != std::string::npos) ++count;
  return count;
}

std::string readTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::filesystem::path freshTempDir(const std::string& name) {
  // ctest runs tests in parallel processes: the running test's own name (or the process id
  // outside a test) keeps one test from wiping a folder another is writing into.
  std::string owner = "pid" + std::to_string(::getpid());
  if (const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info())
    owner = std::string(test->test_suite_name()) + "." + test->name();
  for (char& c : owner)
    if (c == '/') c = '_';  // parameterised test names contain '/'
  std::filesystem::path dir = binaryDir() / "test-tmp" / owner / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void writeFile(const std::filesystem::path& path, const std::string& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace testing_support
