#include "fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "engine/core/log.h"

namespace fuzz {

namespace fs = std::filesystem;

namespace {

fs::path& scratch() {
  static fs::path dir;
  return dir;
}

void removeScratch() {
  std::error_code ignored;
  if (!scratch().empty()) fs::remove_all(scratch(), ignored);
}

}  // namespace

void initialise() {
  if (!scratch().empty()) return;
  eng::setLogSink([](eng::LogLevel, std::string_view) {});
  // /dev/shm when there is one: the loaders read every input from disk.
  const char* base = fs::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  std::string pattern = std::string(base) + "/facial-fuzz-XXXXXX";
  if (!mkdtemp(pattern.data())) {
    std::perror("facial fuzz: cannot create a temporary folder");
    std::abort();
  }
  scratch() = pattern;
  std::atexit(removeScratch);
}

const fs::path& scratchDir() { return scratch(); }

fs::path writeInput(std::string_view name, const uint8_t* data, size_t size) {
  return writeInput(name, std::string_view(reinterpret_cast<const char*>(data), size));
}

fs::path writeInput(std::string_view name, std::string_view text) {
  const fs::path path = scratch() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) {
    std::fprintf(stderr, "facial fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

fs::path sourceDir() { return FACIAL_SOURCE_DIR; }

void propertyFailed(const char* expression, const char* file, int line, const std::string& detail) {
  std::fprintf(stderr, "%s:%d: property does not hold: %s\n  %s\n", file, line, expression, detail.c_str());
  std::abort();
}

}  // namespace fuzz

// libFuzzer calls this once before the first input (every fuzzer links it).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::initialise();
  return 0;
}
