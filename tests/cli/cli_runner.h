#pragma once
// Runs the built `facial` program (<build>/bin/facial) as a child process
// with Vulkan validation on (FACIAL_VALIDATION=1), capturing its exit code,
// stdout and stderr.
#include <filesystem>
#include <string>
#include <vector>

namespace cli_test {

struct CommandOutput {
  int exitCode = -1;  // -1: did not exit normally (signal)
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
