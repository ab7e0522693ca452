// `facial dataset`: a tiny dataset rendered with validation on; labels whose
// landmarks sit on the face; two shards plus the merge equal the unsharded
// run file for file; a rerun completes what a killed or failed run left; bad
// input is one line naming the spec and the field, with nothing written.
#include <algorithm>
#include <fstream>
#include <map>
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

// Transparent backdrop: a landmark on the face lands on a covered pixel
// (alpha from coverage), however dark (a pupil, an open mouth).
const std::string kTinySpec = R"({"format": "facial-dataset-spec", "version": 1, "count": 5, "seed": 11, "size": "96x96",
  "emotions": ["neutral", "happy", "surprise", "happily surprised"], "intensity": [0.6, 1.0],
  "auMix": {"probability": 0.5, "units": [1, 2], "weight": [0.3, 0.6]},
  "yaw": [-25, 25], "pitch": [-10, 10], "lights": ["studio", "left"], "backgrounds": ["transparent"], "quality": "fast"})";

std::vector<nlohmann::json> readLines(const fs::path& path) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(testing_support::readTextFile(path));
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

// Every file under `dir` (relative path -> bytes), for file-for-file checks.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = testing_support::readTextFile(entry.path());
  return files;
}

class DatasetCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing_support::freshTempDir("dataset_command");
    spec_ = dir_ / "tiny.json";
    testing_support::writeFile(spec_, kTinySpec);
  }
  CommandOutput dataset(const fs::path& out, std::vector<std::string> extra = {}, std::vector<std::string> env = {}) {
    std::vector<std::string> args{"dataset", "--spec", spec_.string(), "--out", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return runFacial(args, env);
  }
  fs::path dir_, spec_;
};

TEST_F(DatasetCommand, LabelsDescribeTheImagesAndTheirLandmarksSitOnTheFace) {
  const fs::path out = dir_ / "set";
  const CommandOutput run = dataset(out);
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_NE(run.out.find("shard 0/1 of " + out.string() + ": 5 items, 5 made, 0 already there"), std::string::npos) << run.out;
  const std::vector<nlohmann::json> labels = readLines(out / "labels.jsonl");
  ASSERT_EQ(labels.size(), 5u);
  for (size_t k = 0; k < labels.size(); ++k) {
    const nlohmann::json& label = labels[k];
    EXPECT_EQ(label["index"], k);
    const eng::Image image = readPngOrFail(out / label["image"].get<std::string>());
    ASSERT_EQ(image.width, 96);
    ASSERT_EQ(label["landmarks68"].size(), 68u);
    EXPECT_EQ(label["headPose"]["yaw"], label["camera"]["yaw"]);
    EXPECT_FALSE(label["actionUnits"].empty() && label["emotion"] != "neutral") << label.dump();
    // Brows, nose, eyes and lips (17..67): on the face, never on the backdrop
    // (within a pixel: the far brow's end sits on the silhouette of a turned head).
    for (size_t i = 17; i < 68; ++i) {
      const int x = int(label["landmarks68"][i][0].get<double>()), y = int(label["landmarks68"][i][1].get<double>());
      ASSERT_TRUE(x >= 1 && y >= 1 && x < 95 && y < 95) << "item " << k << " landmark " << i;
      int covered = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) covered = std::max<int>(covered, image.rgba8[(size_t(y + dy) * 96 + size_t(x + dx)) * 4 + 3]);
      EXPECT_EQ(covered, 255) << "item " << k << " landmark " << i << " at " << x << "," << y << " is off the face";
    }
    const auto& box = label["faceBox"];
    EXPECT_GT(box[2].get<double>() - box[0].get<double>(), 25.0) << "face box of item " << k;
  }
  const nlohmann::json index = nlohmann::json::parse(testing_support::readTextFile(out / "index.json"));
  EXPECT_EQ(index["count"], 5);
  EXPECT_EQ(index["complete"], true);
  EXPECT_EQ(index["shards"], nlohmann::json::array({"0/1"}));
}

TEST_F(DatasetCommand, TwoShardsPlusTheMergeEqualTheUnshardedRunFileForFile) {
  const fs::path whole = dir_ / "whole", sharded = dir_ / "sharded";
  ASSERT_TRUE(ranCleanly(dataset(whole)));
  const CommandOutput first = dataset(sharded, {"--shard", "0/2"});
  ASSERT_TRUE(ranCleanly(first));
  EXPECT_NE(first.out.find("3 items, 3 made"), std::string::npos) << first.out;
  EXPECT_FALSE(fs::exists(sharded / "labels.jsonl"));  // a shard does not merge
  // The second shard from a Slurm array's variables (tasks numbered from 1).
  const CommandOutput second = dataset(sharded, {}, {"SLURM_ARRAY_TASK_ID=2", "SLURM_ARRAY_TASK_COUNT=2", "SLURM_ARRAY_TASK_MIN=1"});
  ASSERT_TRUE(ranCleanly(second));
  EXPECT_NE(second.out.find("shard 1/2"), std::string::npos) << second.out;
  const CommandOutput merge = runFacial({"dataset", "merge", "--out", sharded.string()});
  ASSERT_EQ(merge.exitCode, 0) << merge.err;
  EXPECT_NE(merge.out.find("merged 5 items"), std::string::npos) << merge.out;

  auto a = filesUnder(whole / "images"), b = filesUnder(sharded / "images");
  EXPECT_EQ(a.size(), 5u);
  EXPECT_TRUE(a == b) << "the shards' images differ from the unsharded run's";
  EXPECT_EQ(testing_support::readTextFile(whole / "labels.jsonl"), testing_support::readTextFile(sharded / "labels.jsonl"));
  EXPECT_TRUE(filesUnder(whole / "labels") == filesUnder(sharded / "labels"));
  const nlohmann::json index = nlohmann::json::parse(testing_support::readTextFile(sharded / "index.json"));
  EXPECT_EQ(index["shards"], nlohmann::json::array({"0/2", "1/2"}));
  EXPECT_EQ(index["specHash"], nlohmann::json::parse(testing_support::readTextFile(whole / "index.json"))["specHash"]);
}

TEST_F(DatasetCommand, ARerunCompletesWhatAKilledRunLeft) {
  const fs::path out = dir_ / "set";
  ASSERT_TRUE(ranCleanly(dataset(out)));
  const auto before = filesUnder(out / "images");
  const std::string labels = testing_support::readTextFile(out / "labels.jsonl");
  // What a worker killed mid-item leaves: an image without its label, a
  // label gone, a partial file.
  fs::remove(out / "labels/000001.json");
  fs::remove(out / "images/000003.png");
  fs::remove(out / "labels.jsonl");
  testing_support::writeFile(out / "images/000004.12345.partial.png", "half a png");
  const CommandOutput rerun = dataset(out);
  ASSERT_TRUE(ranCleanly(rerun));
  EXPECT_NE(rerun.out.find("5 items, 2 made, 3 already there"), std::string::npos) << rerun.out;
  EXPECT_TRUE(filesUnder(out / "images") == before);
  EXPECT_EQ(testing_support::readTextFile(out / "labels.jsonl"), labels);
  EXPECT_EQ(testing_support::partialFilesIn(out / "images"), 0u);
}

TEST_F(DatasetCommand, AWorkerKilledMidRunIsFinishedByARerun) {
  const fs::path reference = dir_ / "reference", out = dir_ / "killed";
  // 40 items, so that the kill after the second lands well before the end on
  // a quiet machine too (5 items could all be finished within one 0.1 s poll).
  std::string longer = kTinySpec;
  const std::string five = "\"count\": 5";
  longer.replace(longer.find(five), five.size(), "\"count\": 40");
  spec_ = dir_ / "longer.json";
  testing_support::writeFile(spec_, longer);
  ASSERT_TRUE(ranCleanly(dataset(reference)));
  // SIGKILL once the second item is finished (at most a minute of waiting).
  const std::string script =
      "\"$0\" dataset --spec \"$1\" --out \"$2\" & pid=$!; n=0; "
      "while [ ! -e \"$2/labels/000001.json\" ] && [ $n -lt 600 ]; do sleep 0.1; n=$((n+1)); done; "
      "kill -9 $pid; wait $pid; exit 0";
  const CommandOutput killed = runProgram("/bin/sh", {"-c", script, facialProgram().string(), spec_.string(), out.string()});
  ASSERT_EQ(killed.exitCode, 0) << killed.err;
  ASSERT_FALSE(fs::exists(out / "labels.jsonl")) << "the run finished before it was killed";
  const CommandOutput rerun = dataset(out);
  ASSERT_TRUE(ranCleanly(rerun));
  EXPECT_NE(rerun.out.find("already there"), std::string::npos) << rerun.out;
  EXPECT_TRUE(filesUnder(out / "images") == filesUnder(reference / "images"));
  EXPECT_EQ(testing_support::readTextFile(out / "labels.jsonl"), testing_support::readTextFile(reference / "labels.jsonl"));
  EXPECT_EQ(testing_support::partialFilesIn(out / "images") + testing_support::partialFilesIn(out / "labels"), 0u);
}

TEST_F(DatasetCommand, AFailedWriteNamesTheFileAndLeavesNothingHalfWritten) {
  const fs::path out = dir_ / "full";
  // A full disk, as the process sees it: writes past 2 KiB fail (EFBIG).
  const CommandOutput full = runProgram("/bin/sh",
                                        {"-c", "ulimit -f 4; trap '' XFSZ; exec \"$0\" \"$@\"", facialProgram().string(),
                                         "dataset", "--spec", spec_.string(), "--out", out.string()},
                                        {"FACIAL_VALIDATION=1"});
  EXPECT_EQ(full.exitCode, 1) << full.err;
  EXPECT_NE(full.err.find("facial dataset: error: "), std::string::npos) << full.err;
  EXPECT_NE(full.err.find("images/0000"), std::string::npos) << full.err;
  EXPECT_EQ(testing_support::partialFilesIn(out / "images"), 0u);
  EXPECT_FALSE(fs::exists(out / "labels.jsonl"));
  for (const auto& entry : fs::directory_iterator(out / "images"))  // whatever is there is whole
    EXPECT_EQ(readPngOrFail(entry.path()).width, 96) << entry.path();
  // With room again, the same command finishes the set.
  ASSERT_TRUE(ranCleanly(dataset(out)));
  EXPECT_EQ(readLines(out / "labels.jsonl").size(), 5u);
}

TEST_F(DatasetCommand, MergeNamesTheMissingItems) {
  const fs::path out = dir_ / "half";
  ASSERT_TRUE(ranCleanly(dataset(out, {"--shard", "0/2"})));
  const CommandOutput merge = runFacial({"dataset", "--merge", "--out", out.string()});
  EXPECT_EQ(merge.exitCode, 1);
  EXPECT_EQ(countOccurrences(merge.err, "\n"), 1u) << merge.err;
  EXPECT_NE(merge.err.find("2 of 5 items missing (1, 3); shard label lists seen: 0/2"), std::string::npos) << merge.err;
  EXPECT_FALSE(fs::exists(out / "labels.jsonl"));
  const nlohmann::json index = nlohmann::json::parse(testing_support::readTextFile(out / "index.json"));
  EXPECT_EQ(index["complete"], false);
  EXPECT_EQ(index["missing"], nlohmann::json::array({1, 3}));
}

// One line on stderr naming the source and the problem; no dataset folder made.
void expectRefused(const CommandOutput& run, const std::string& message, const fs::path& out) {
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_EQ(countOccurrences(run.err, "\n"), 1u) << run.err;
  EXPECT_NE(run.err.find("facial dataset: error: "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out / "spec.json")) << "written despite the error: " << message;
}

TEST_F(DatasetCommand, BadInputIsOneLineNamingTheSpecAndTheField) {
  const fs::path out = dir_ / "never";
  testing_support::writeFile(dir_ / "bad.json", R"({"count": 4, "emotions": ["happy", "smug"]})");
  expectRefused(runFacial({"dataset", "--spec", (dir_ / "bad.json").string(), "--out", out.string()}),
                "bad.json: /emotions/1: unknown emotion 'smug'", out);
  testing_support::writeFile(dir_ / "model.json", R"({"count": 4, "models": ["missing.glb"]})");
  expectRefused(runFacial({"dataset", "--spec", (dir_ / "model.json").string(), "--out", out.string()}),
                "model.json: /models/0: no such model file", out);
  testing_support::writeFile(dir_ / "range.json", R"({"count": 4, "pitch": [10, -10]})");
  expectRefused(runFacial({"dataset", "--spec", (dir_ / "range.json").string(), "--out", out.string()}),
                "range.json: /pitch: min 10 is above max -10", out);
  expectRefused(dataset(out, {"--count", "0"}), "/count: must be at least 1", out);
  expectRefused(dataset(out, {"--size", "0x0"}), "--size: '0x0'", out);
  expectRefused(dataset(out, {"--shard", "2/2"}), "--shard: '2/2' is out of range", out);
  expectRefused(dataset(out, {}, {"JOB_COMPLETION_INDEX=4", "FACIAL_SHARD_COUNT=4"}), "JOB_COMPLETION_INDEX=4", out);
  expectRefused(runFacial({"dataset", "--spec", (dir_ / "none.json").string(), "--out", out.string()}), "none.json", out);
  expectRefused(runFacial({"dataset", "--count", "3", "--emotions", "happy,glee", "--out", out.string()}),
                "command line: /emotions/1: unknown emotion 'glee'", out);
}

TEST_F(DatasetCommand, AFolderRefusesADifferentSpec) {
  const fs::path out = dir_ / "set";
  ASSERT_TRUE(ranCleanly(dataset(out, {"--count", "1"})));
  const CommandOutput other = dataset(out, {"--count", "2"});
  EXPECT_EQ(other.exitCode, 1);
  EXPECT_NE(other.err.find("was made from another spec"), std::string::npos) << other.err;
}

}  // namespace
}  // namespace cli_test
