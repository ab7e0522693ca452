#pragma once
// Shared by the libFuzzer targets in fuzz/: the loaders read files, so each
// input is written to a file in a private temporary folder first, and the
// log is silenced (a hostile file's warnings would drown libFuzzer's output).
//
// A fuzzer fails on what libFuzzer catches (crash, ASan/UBSan report, leak,
// timeout, out-of-memory) and on the properties it checks with
// FUZZ_PROPERTY: what a loader accepts must be consistent for the code that
// uses it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace fuzz {

// Once per process (LLVMFuzzerInitialize, defined in fuzz_support.cpp, calls
// it): silences eng::log and creates the temporary folder.
void initialise();
// The private temporary folder (removed at exit).
const std::filesystem::path& scratchDir();
// Writes data to scratchDir()/name and returns the path.
std::filesystem::path writeInput(std::string_view name, const uint8_t* data, size_t size);
std::filesystem::path writeInput(std::string_view name, std::string_view text);
// The project's source folder (data/ for presets).
std::filesystem::path sourceDir();

// Prints the property that does not hold and aborts (libFuzzer saves the input).
[[noreturn]] void propertyFailed(const char* expression, const char* file, int line, const std::string& detail);

}  // namespace fuzz

#define FUZZ_PROPERTY(condition, detail)                                         \
  do {                                                                           \
    if (!(condition)) ::fuzz::propertyFailed(#condition, __FILE__, __LINE__, detail); \
  } while (0)
