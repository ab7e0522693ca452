// The program's own front end (cli/main.cpp): subcommand dispatch and exit codes.
#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"

namespace cli_test {
namespace {

TEST(FacialProgram, UnknownCommandFailsEvenWithHelp) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"nosuch"}, {"nosuch", "--help"}}) {
    const CommandOutput run = runFacial(args);
    EXPECT_EQ(run.exitCode, 2) << args.size();
    EXPECT_NE(run.err.find("unknown command 'nosuch'"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("render"), std::string::npos) << "the message lists the commands: " << run.err;
  }
}

TEST(FacialProgram, HelpOfAKnownCommandSucceeds) {
  const CommandOutput run = runFacial({"render", "--help"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("--out"), std::string::npos);
}

TEST(FacialProgram, NoCommandFails) {
  EXPECT_NE(runFacial({}).exitCode, 0);
}

}  // namespace
}  // namespace cli_test
