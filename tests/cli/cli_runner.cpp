#include "tests/cli/cli_runner.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/common/test_support.h"

namespace cli_test {
namespace {

// POSIX shell single quoting: every byte literal.
std::string shellQuote(const std::string& arg) {
  std::string quoted = "'";
  for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

std::filesystem::path facialProgram() { return testing_support::binaryDir() / "bin" / "facial"; }

CommandOutput runFacial(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
  std::vector<std::string> assignments{"FACIAL_VALIDATION=1"};
  assignments.insert(assignments.end(), environment.begin(), environment.end());
  return runProgram(facialProgram(), args, assignments);
}

CommandOutput runProgram(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::vector<std::string>& environment) {
  static int runs = 0;
  const std::filesystem::path dir = testing_support::binaryDir() / "test-tmp" / "cli-runs";
  std::filesystem::create_directories(dir);
  const std::string stem = "run" + std::to_string(::getpid()) + "_" + std::to_string(runs++);
  const std::filesystem::path outFile = dir / (stem + ".out"), errFile = dir / (stem + ".err");
  std::string command = "env";
  for (const std::string& assignment : environment) command += " " + shellQuote(assignment);
  command += " " + shellQuote(program.string());
  for (const std::string& arg : args) command += " " + shellQuote(arg);
  command += " >" + shellQuote(outFile.string()) + " 2>" + shellQuote(errFile.string()) + " </dev/null";
  const int status = std::system(command.c_str());
  CommandOutput result;
  result.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  result.out = readAll(outFile);
  result.err = readAll(errFile);
  std::filesystem::remove(outFile);
  std::filesystem::remove(errFile);
  // A crash is never a refusal, whatever the test expects of the exit code:
  // the shell reports a child killed by signal N as 128 + N.
  if (result.exitCode >= 128 || result.exitCode == -1) {
    std::string line = program.filename().string();
    for (const std::string& arg : args) line += " " + arg;
    ADD_FAILURE() << line << ": "
                  << (result.exitCode >= 128 ? "killed by signal " + std::to_string(result.exitCode - 128) + " (a crash, not an exit)"
                                             : std::string("did not exit normally"))
                  << "\n" << result.err;
  }
  return result;
}

size_t countOccurrences(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++count;
  return count;
}

}  // namespace cli_test
