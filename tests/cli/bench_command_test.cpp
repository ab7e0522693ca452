// `facial bench frames`: one result line ending with fps=<positive number>,
// static and animated frames, instanced crowds, and one clear error line for
// bad input. Small images and few frames keep it fast on lavapipe.
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"

namespace cli_test {
namespace {

// The last non-empty line of `text`.
std::string lastLine(const std::string& text) {
  size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const size_t begin = text.rfind('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin == std::string::npos ? 0 : begin + 1) + 1);
}

// The number after the last " fps=" of a line that ends with it; -1 when the
// line does not end with one.
double fpsOf(const std::string& line) {
  const size_t at = line.rfind(" fps=");
  if (at == std::string::npos) return -1.0;
  const std::string number = line.substr(at + 5);
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  return (end != number.c_str() && *end == '\0') ? value : -1.0;
}

CommandOutput bench(const std::vector<std::string>& extra, const std::string& model) {
  std::vector<std::string> args{"bench", "frames", model, "--size", "64x64", "--frames", "5", "--warmup", "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  return runFacial(args);
}

TEST(BenchCommand, AnimatedFramesReportFpsAndSettings) {
  const std::string face = writeTestFace("bench_command_face").string();
  const CommandOutput run = bench({}, face);
  ASSERT_TRUE(ranCleanly(run)) << run.err;
  const std::string line = lastLine(run.out);
  EXPECT_EQ(line.rfind("bench frames test_face.glb ", 0), 0u) << run.out;
  EXPECT_NE(line.find(" 64x64 quality=high msaa="), std::string::npos) << line;
  EXPECT_NE(line.find(" instances=1 animate=all "), std::string::npos) << line;
  EXPECT_NE(line.find(" cpu_median_ms="), std::string::npos) << line;
  EXPECT_GT(fpsOf(line), 0.0) << line;
  EXPECT_NE(run.out.find("settings: quality=high msaa="), std::string::npos) << run.out;
  EXPECT_NE(line.find(" quality=high msaa="), std::string::npos) << line;
  EXPECT_NE(run.out.find("memory: asset_buffer_bytes="), std::string::npos) << run.out;
  // Every target active: the active list holds all of them.
  const size_t targets = line.find(" targets=");
  ASSERT_NE(targets, std::string::npos) << line;
  const std::string count = line.substr(targets + 9, line.find(' ', targets + 9) - (targets + 9));
  EXPECT_NE(count, "0") << line;
  EXPECT_NE(run.out.find(" active_weights=" + count + " "), std::string::npos) << run.out;
}

TEST(BenchCommand, StaticFramesWork) {
  const std::string face = writeTestFace("bench_command_static").string();
  const CommandOutput run = bench({"--animate", "none"}, face);
  ASSERT_TRUE(ranCleanly(run)) << run.err;
  const std::string line = lastLine(run.out);
  EXPECT_NE(line.find(" animate=none "), std::string::npos) << line;
  EXPECT_NE(run.out.find(" active_weights=0 "), std::string::npos) << run.out;
  EXPECT_GT(fpsOf(line), 0.0) << line;
}

TEST(BenchCommand, InstancesShareOneInstancedDraw) {
  const std::string head = std::string(FACIAL_SOURCE_DIR) + "/data/head.glb";
  const CommandOutput one = bench({}, head);
  const CommandOutput four = bench({"--instances", "4"}, head);
  ASSERT_TRUE(ranCleanly(one)) << one.err;
  ASSERT_TRUE(ranCleanly(four)) << four.err;
  EXPECT_NE(lastLine(four.out).find(" instances=4 "), std::string::npos) << four.out;
  EXPECT_GT(fpsOf(lastLine(four.out)), 0.0) << four.out;
  // Same draw count for 1 and 4 instances: one instanced draw per primitive.
  const auto draws = [](const std::string& out) {
    const size_t at = out.find(" draws=");
    return at == std::string::npos ? std::string() : out.substr(at, out.find(' ', at + 1) - at);
  };
  EXPECT_FALSE(draws(one.out).empty()) << one.out;
  EXPECT_EQ(draws(one.out), draws(four.out));
}

TEST(BenchCommand, FastTierSaysWhatItRan) {
  const std::string face = writeTestFace("bench_command_fast").string();
  const CommandOutput run = bench({"--quality", "fast"}, face);
  ASSERT_TRUE(ranCleanly(run)) << run.err;
  const std::string line = lastLine(run.out);
  EXPECT_NE(line.find(" quality=fast msaa=1 "), std::string::npos) << line;
  EXPECT_NE(run.out.find(" shadow_map=0 "), std::string::npos) << run.out;
  EXPECT_GT(fpsOf(line), 0.0) << line;
}

// The number after " key=" in `text`; -1 when absent.
long long valueOf(const std::string& text, const std::string& key) {
  const size_t at = text.find(" " + key + "=");
  if (at == std::string::npos) return -1;
  return std::atoll(text.c_str() + at + key.size() + 2);
}

TEST(BenchCommand, LevelOfDetailDrawsFewerTrianglesAndSaysSo) {
  const std::string head = std::string(FACIAL_SOURCE_DIR) + "/data/head.glb";
  const CommandOutput full = bench({"--animate", "none"}, head);
  const CommandOutput lod = bench({"--animate", "none", "--lod-error", "1"}, head);
  ASSERT_TRUE(ranCleanly(full)) << full.err;
  ASSERT_TRUE(ranCleanly(lod)) << lod.err;
  EXPECT_NE(full.out.find(" lod_error=0 "), std::string::npos) << full.out;
  EXPECT_NE(full.out.find(" coarser_draws=0 "), std::string::npos) << full.out;
  EXPECT_NE(lod.out.find(" lod_error=1 "), std::string::npos) << lod.out;
  const long long all = valueOf(lastLine(full.out), "triangles"), fewer = valueOf(lastLine(lod.out), "triangles");
  EXPECT_GT(all, 60000) << full.out;  // the built-in head, every triangle
  EXPECT_GT(fewer, 0) << lod.out;
  EXPECT_LT(fewer, all / 2) << "64x64 pixels cannot show the head's 71k triangles";
  EXPECT_GT(valueOf(lod.out, "coarser_draws"), 0) << lod.out;
}

// ---- Bad input: one clear error line, non-zero exit ----

void expectOneErrorLine(const CommandOutput& run, const std::string& expected) {
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("facial bench frames: error: " + expected), std::string::npos) << run.err;
  EXPECT_EQ(countOccurrences(run.err, "error:"), 1u) << run.err;
  EXPECT_EQ(run.out.find("fps="), std::string::npos) << run.out;
}

TEST(BenchCommandValidity, MissingFileIsNamed) {
  const std::string missing = "/nonexistent/bench_missing.glb";
  expectOneErrorLine(bench({}, missing), missing);
}

TEST(BenchCommandValidity, LodErrorOutOfRangeIsRejected) {
  const std::string face = writeTestFace("bench_command_bad").string();
  expectOneErrorLine(runFacial({"bench", "frames", face, "--lod-error", "100"}), "--lod-error 100");
}

TEST(BenchCommandValidity, ZeroFramesIsRejected) {
  const std::string face = writeTestFace("bench_command_bad").string();
  expectOneErrorLine(runFacial({"bench", "frames", face, "--frames", "0"}), "--frames 0 is out of range");
}

TEST(BenchCommandValidity, JunkSizeIsRejected) {
  const std::string face = writeTestFace("bench_command_bad").string();
  expectOneErrorLine(runFacial({"bench", "frames", face, "--size", "junk"}), "--size 'junk' is not WxH");
}

TEST(BenchCommandValidity, JunkAnimateIsRejected) {
  const std::string face = writeTestFace("bench_command_bad").string();
  expectOneErrorLine(runFacial({"bench", "frames", face, "--animate", "junk"}), "--animate 'junk' is not all or none");
}

TEST(BenchCommandValidity, JunkQualityIsRejected) {
  const std::string face = writeTestFace("bench_command_bad").string();
  expectOneErrorLine(runFacial({"bench", "frames", face, "--quality", "ultra"}),
                     "--quality 'ultra' is not auto, fast, balanced or high");
}

}  // namespace
}  // namespace cli_test
