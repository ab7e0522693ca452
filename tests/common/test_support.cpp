#include "tests/common/test_support.h"

#include <fstream>

namespace testing_support {

std::filesystem::path sharedDir() {
  std::filesystem::path p = FACIAL_SHARED_DIR;
  std::error_code ec;
  return std::filesystem::is_directory(p / "assets", ec) ? p : std::filesystem::path{};
}

std::filesystem::path sourceDir() { return FACIAL_SOURCE_DIR; }
std::filesystem::path binaryDir() { return FACIAL_BINARY_DIR; }

std::filesystem::path freshTempDir(const std::string& name) {
  std::filesystem::path dir = binaryDir() / "test-tmp" / name;
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
