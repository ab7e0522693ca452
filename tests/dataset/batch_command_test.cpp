// `facial batch`: jobs run in order, one result line each; a failing job is
// recorded and the rest still run; exit 1 when any failed; --shard runs every
// Nth job.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {
namespace fs = std::filesystem;

std::vector<nlohmann::json> resultLines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

class BatchCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing_support::freshTempDir("batch_command");
    const std::string d = dir_.string();
    testing_support::writeFile(dir_ / "manifest.jsonl",
        "# two expressions, a broken line, a failing job, a tiny dataset\n"
        "{\"kind\": \"express\", \"args\": [\"happy\", \"--size\", \"64x64\", \"--out\", \"" + d + "/happy.png\"]}\n"
        "{\"kind\": \"juggle\", \"args\": []}\n"
        "{\"kind\": \"express\", \"args\": [\"smug\", \"--size\", \"64x64\", \"--out\", \"" + d + "/smug.png\"]}\n"
        "{\"kind\": \"dataset\", \"args\": [\"--count\", \"2\", \"--size\", \"48x48\", \"--out\", \"" + d + "/set\"]}\n");
  }
  fs::path dir_;
};

TEST_F(BatchCommand, RunsEveryJobAndRecordsFailures) {
  const CommandOutput run = runFacial({"batch", (dir_ / "manifest.jsonl").string(), "--results", (dir_ / "r.jsonl").string()});
  EXPECT_EQ(run.exitCode, 1) << run.err;
  const std::vector<nlohmann::json> results = resultLines(run.out);
  ASSERT_EQ(results.size(), 4u) << run.out;
  EXPECT_EQ(testing_support::readTextFile(dir_ / "r.jsonl"), run.out);
  for (size_t j = 0; j < results.size(); ++j) EXPECT_EQ(results[j]["job"], j);
  EXPECT_EQ(results[0]["ok"], true);
  EXPECT_EQ(results[0]["output"], (dir_ / "happy.png").string());
  EXPECT_TRUE(results[0]["error"].is_null());
  EXPECT_EQ(results[1]["ok"], false);
  EXPECT_NE(results[1]["error"].get<std::string>().find("line 3: unknown kind 'juggle'"), std::string::npos);
  EXPECT_EQ(results[2]["ok"], false);
  EXPECT_NE(results[2]["error"].get<std::string>().find("facial express: error: "), std::string::npos) << results[2];
  EXPECT_NE(results[2]["error"].get<std::string>().find("smug"), std::string::npos) << results[2];
  EXPECT_EQ(results[3]["ok"], true) << results[3];
  EXPECT_GT(results[3]["seconds"].get<double>(), 0.0);
  EXPECT_EQ(readPngOrFail(dir_ / "happy.png").width, 64);
  EXPECT_TRUE(fs::exists(dir_ / "set" / "labels.jsonl"));
  EXPECT_NE(run.err.find("4 of 4 jobs ran in shard 0/1, 2 failed"), std::string::npos) << run.err;
}

TEST_F(BatchCommand, AShardRunsEveryNthJob) {
  // Shard 0/2: jobs 0 and 2 (the scheduler's variables reach the batch, not its jobs).
  const CommandOutput run = runFacial({"batch", (dir_ / "manifest.jsonl").string()},
                                      {"JOB_COMPLETION_INDEX=0", "FACIAL_SHARD_COUNT=2"});
  EXPECT_EQ(run.exitCode, 1) << run.err;
  const std::vector<nlohmann::json> results = resultLines(run.out);
  ASSERT_EQ(results.size(), 2u) << run.out;
  EXPECT_EQ(results[0]["job"], 0);
  EXPECT_EQ(results[1]["job"], 2);
  EXPECT_FALSE(fs::exists(dir_ / "set"));
}

TEST_F(BatchCommand, AMissingManifestIsOneLine) {
  const CommandOutput run = runFacial({"batch", (dir_ / "none.jsonl").string()});
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(countOccurrences(run.err, "\n"), 1u) << run.err;
  EXPECT_NE(run.err.find("none.jsonl"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace cli_test
