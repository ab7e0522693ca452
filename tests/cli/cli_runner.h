#pragma once
// Runs the built `facial` program (<build>/bin/facial) as a child process
// with Vulkan validation on (FACIAL_VALIDATION=1), capturing its exit code,
// stdout and stderr. A child killed by a signal (a crash) fails the test.
#include <filesystem>
#include <string>
#include <vector>

namespace cli_test {

struct CommandOutput {
  int exitCode = -1;  // -1 or 128 + N: killed (signal N), already a test failure
  std::string out;
  std::string err;
};

std::filesystem::path facialProgram();
// `environment`: extra NAME=VALUE assignments for the child.
CommandOutput runFacial(const std::vector<std::string>& args, const std::vector<std::string>& environment = {});
// Any program, with only the given extra NAME=VALUE assignments.
CommandOutput runProgram(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::vector<std::string>& environment = {});

// How many times `needle` occurs in `text`.
size_t countOccurrences(const std::string& text, const std::string& needle);

}  // namespace cli_test
