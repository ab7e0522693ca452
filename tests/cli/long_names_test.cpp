// A hostile name never floods the terminal (issue 37): warnings that quote a
// name from a file and CLI11's usage errors that quote an argument are
// shortened by the one home for it (app::shortenNames, app/program_error.h).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/program_error.h"
#include "tests/cli/cli_runner.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

TEST(LongNames, EachLineIsShortenedOnItsOwn) {
  const std::string text = "bad value " + std::string(100'000, 'x') + "\nRun with --help for more information.\n";
  const std::string shortened = app::shortenEachLine(text);
  EXPECT_LE(shortened.size(), 400u);
  EXPECT_NE(shortened.find("...(100000 bytes)..."), std::string::npos) << shortened;
  EXPECT_TRUE(shortened.ends_with("\nRun with --help for more information.\n")) << shortened;
  EXPECT_EQ(app::shortenEachLine("one\ntwo"), "one\ntwo\n");
}

// Linux takes arguments up to 128 KB each.
TEST(LongNames, ACommandLineErrorQuotesALongArgumentShortened) {
  const CommandOutput run = runFacial({"info", "m.glb", std::string(100'000, 'o')});  // an unexpected extra argument
  EXPECT_NE(run.exitCode, 0);
  EXPECT_LE(run.err.size(), 1000u) << run.err.substr(0, 1000);
  EXPECT_NE(run.err.find("bytes)..."), std::string::npos) << run.err.substr(0, 1000);
}

// A node named with 1 MB refers to a skin the file lacks: the loader warns, naming the node.
TEST(LongNames, AWarningQuotingANameFromTheFileIsShortened) {
  const std::filesystem::path dir = testing_support::freshTempDir("long_names");
  const std::string name(1 << 20, 'n');
  const nlohmann::json doc = {{"asset", {{"version", "2.0"}}},
                              {"nodes", nlohmann::json::array({{{"name", name}, {"skin", 3}}})},
                              {"scenes", nlohmann::json::array({{{"nodes", {0}}}})},
                              {"scene", 0}};
  testing_support::writeFile(dir / "named.gltf", doc.dump());
  const CommandOutput run = runFacial({"info", (dir / "named.gltf").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err.substr(0, 1000);
  EXPECT_NE(run.out.find("refers to skin 3"), std::string::npos) << run.out.substr(0, 2000);
  EXPECT_LE(run.out.size() + run.err.size(), 20'000u) << run.out.substr(0, 2000);
}

}  // namespace
}  // namespace cli_test
