// Files (issue 37): an output that resolves to an input is refused before any
// work, in every command that writes; frame folders are written whole; names
// in error lines are shortened; weights outside [-10, 10] are refused.
#include "app/output_paths.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/program_error.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

// Its own namespace: test files are compiled several to a unit.
namespace cli_test::output_paths {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> filesIn(const fs::path& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

// Exit 1 and exactly one line on stderr.
::testing::AssertionResult failedInOneLine(const CommandOutput& run) {
  if (run.exitCode != 1) return ::testing::AssertionFailure() << "exit " << run.exitCode << ", stderr: " << run.err;
  if (run.err.empty() || run.err.back() != '\n' || std::count(run.err.begin(), run.err.end(), '\n') != 1)
    return ::testing::AssertionFailure() << "not one line: " << run.err.substr(0, 4000);
  return ::testing::AssertionSuccess();
}

constexpr const char* kTimeline =
    R"({"version": 1, "duration": 1, "tracks": [{"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})";

TEST(OutputPaths, AnOutputThatResolvesToAnInputIsRefused) {
  const fs::path dir = testing_support::freshTempDir("output_paths_same");
  testing_support::writeFile(dir / "m.glb", "model");
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "m.glb", dir / "link.glb");
  fs::create_hard_link(dir / "m.glb", dir / "hard.glb");
  const std::string input = (dir / "m.glb").string();
  for (const fs::path& out : {dir / "m.glb", dir / "sub" / ".." / "m.glb", dir / "link.glb", dir / "hard.glb"}) {
    auto checked = app::checkOutputs({.inputs = {{"model", input}}, .outputs = {{"--out", out.native()}}});
    ASSERT_FALSE(checked.ok()) << out;
    EXPECT_EQ(checked.error().message, "--out '" + out.string() + "' is the input model '" + input +
                                           "': writing it would replace what is read; nothing was written");
  }
  // Relative to the working directory, too.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir / "sub");
  auto relative = app::checkOutputs({.inputs = {{"model", input}}, .outputs = {{"--out", "../m.glb"}}});
  fs::current_path(cwd);
  EXPECT_FALSE(relative.ok());

  EXPECT_TRUE(app::checkOutputs({.inputs = {{"model", input}, {"--rigmap", ""}}, .outputs = {{"--out", (dir / "new.png").native()}}}).ok());
  auto twice = app::checkOutputs({.outputs = {{"--out", (dir / "a.wav").native()}, {"--wav", (dir / "sub/../a.wav").native()}}});
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.error().message.find("is also --out"), std::string::npos) << twice.error().message;
}

TEST(OutputPaths, AFrameFolderMayNotReplaceAnInput) {
  const fs::path dir = testing_support::freshTempDir("output_paths_frames_input");
  testing_support::writeFile(dir / "frame_0001.png", "an input that looks like a frame");
  testing_support::writeFile(dir / "graph.json", "{}");
  auto refused = app::checkOutputs({.inputs = {{"file", (dir / "frame_0001.png").native()}}, .frameFolders = {{"--out", dir.native()}}});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("holds the input file"), std::string::npos) << refused.error().message;
  // Frames are written beside other files: an input that is not a frame is safe there.
  EXPECT_TRUE(app::checkOutputs({.inputs = {{"file", (dir / "graph.json").native()}}, .frameFolders = {{"--out", dir.native()}}}).ok());
}

TEST(FrameFolder, ANewRunReplacesEveryFrameOfALongerOne) {
  const fs::path dir = testing_support::freshTempDir("frame_folder_replace");
  testing_support::writeFile(dir / "notes.txt", "the user's own file");
  for (const auto& [count, text] : {std::pair{5u, "first"}, std::pair{3u, "second"}}) {
    auto frames = app::FrameFolder::create(dir);
    ASSERT_TRUE(frames.ok()) << frames.error().message;
    for (uint32_t i = 0; i < count; ++i) testing_support::writeFile(frames->framePath(i), text);
    ASSERT_TRUE(frames->commit().ok());
  }
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"frame_0000.png", "frame_0001.png", "frame_0002.png", "notes.txt"}));
  EXPECT_EQ(readText(dir / "frame_0002.png"), "second");
  EXPECT_EQ(readText(dir / "notes.txt"), "the user's own file");
}

TEST(FrameFolder, AFailedRunLeavesTheEarlierFramesAsTheyWere) {
  const fs::path dir = testing_support::freshTempDir("frame_folder_failed");
  {
    auto frames = app::FrameFolder::create(dir);
    ASSERT_TRUE(frames.ok());
    for (uint32_t i = 0; i < 2; ++i) testing_support::writeFile(frames->framePath(i), "kept");
    ASSERT_TRUE(frames->commit().ok());
  }
  {
    auto frames = app::FrameFolder::create(dir);
    ASSERT_TRUE(frames.ok());
    for (uint32_t i = 0; i < 4; ++i) testing_support::writeFile(frames->framePath(i), "lost");
  }  // no commit: the run failed
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"frame_0000.png", "frame_0001.png"}));
  EXPECT_EQ(readText(dir / "frame_0001.png"), "kept");
  // What a killed run left is cleared by the next one.
  testing_support::writeFile(dir / ".partial-frames" / "frame_0007.png", "killed");
  auto frames = app::FrameFolder::create(dir);
  ASSERT_TRUE(frames.ok());
  EXPECT_FALSE(fs::exists(dir / ".partial-frames" / "frame_0007.png"));
}

TEST(FrameFolder, FrameNames) {
  EXPECT_EQ(app::frameFileName(12), "frame_0012.png");
  EXPECT_EQ(app::frameFileName(123456), "frame_123456.png");
  EXPECT_TRUE(app::isFrameFileName("frame_123456.png"));
  for (const char* other : {"frame_012.png", "frame_00a1.png", "frame_0001.png.bak", "my_frame_0001.png", "frame_.png"})
    EXPECT_FALSE(app::isFrameFileName(other)) << other;
}

TEST(ErrorLine, LongNamesAreShortenedInTheMiddle) {
  const std::string name = "/start/" + std::string(10 << 20, 'a') + "/end.glb";
  const std::string line = app::shortenNames(name + ": file not found");
  EXPECT_LE(line.size(), app::kMaxNameInMessage + 32);
  EXPECT_EQ(line.rfind("/start/aaa", 0), 0u) << line;
  // The word is the name and its colon.
  EXPECT_NE(line.find("...(" + std::to_string(name.size() + 1) + " bytes)...aaa"), std::string::npos) << line;
  EXPECT_TRUE(line.ends_with("aaa/end.glb: file not found")) << line;
  EXPECT_EQ(app::shortenNames("m.glb: file not found"), "m.glb: file not found");

  // Many long words: the whole line is bounded too.
  std::string words;
  for (int i = 0; i < 100; ++i) words += std::string(200, 'w') + " ";
  EXPECT_LE(app::shortenNames(words).size(), app::kMaxMessageLine);

  // Cut between UTF-8 characters, never inside one.
  std::string accents;
  for (int i = 0; i < 1000; ++i) accents += "\xc3\xa9";  // é
  const std::string cut = app::elideMiddle(accents, 101);
  const size_t marker = cut.find("...(");
  ASSERT_NE(marker, std::string::npos);
  EXPECT_EQ(marker % 2, 0u);
  EXPECT_EQ((cut.size() - cut.find(")...") - 4) % 2, 0u);
}

// The program side: each command that writes refuses to write over what it reads,
// before reading it (a file that is no model is refused the same way), and
// leaves it as it was.
TEST(FilesCommand, NoCommandWritesOverItsInput) {
  const fs::path dir = testing_support::freshTempDir("files_command_inputs");
  const std::string in = (dir / "in.glb").string(), json = (dir / "t.json").string(), wav = (dir / "a.wav").string();
  const std::string viaDotdot = (dir / "sub" / ".." / "in.glb").string();
  fs::create_directories(dir / "sub");
  const std::vector<std::vector<std::string>> commands = {
      {"render", in, "--out", in},
      {"render", in, "--out", viaDotdot},
      {"express", "happy", "--model", in, "--out", viaDotdot},
      {"sheet", "--model", in, "--out", in},
      {"timeline", "import", in, "--out", in},
      {"timeline", "export", json, "--model", in, "--out", json},
      {"timeline", "export", json, "--model", in, "--out", viaDotdot},
      {"play", json, "--model", in, "--out", (dir / "frames").string(), "--video", json},
      {"say", "--audio", wav, "--model", in, "--out", (dir / "v.mp4").string(), "--wav", wav},
      {"convert", in, "--out", viaDotdot},
      {"make-head", "--landmarks", json, "--out", json},
      {"demo", "--headless", "--graph", json, "--screenshot", json},
  };
  for (const std::vector<std::string>& args : commands) {
    testing_support::writeFile(in, "not a model: the check comes first");
    testing_support::writeFile(json, kTimeline);
    testing_support::writeFile(wav, "RIFF");
    const CommandOutput run = runFacial(args);
    EXPECT_TRUE(failedInOneLine(run)) << args[0] << " " << args[1];
    EXPECT_NE(run.err.find("is the input"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("; nothing was written"), std::string::npos) << run.err;
    EXPECT_EQ(readText(in), "not a model: the check comes first") << args[0];
    EXPECT_EQ(readText(json), kTimeline) << args[0];
    EXPECT_EQ(readText(wav), "RIFF") << args[0];
  }
}

TEST(FilesCommand, AWeightOutsideTheRangeIsRefused) {
  const fs::path face = writeTestFace("files_command_weight_face");
  const fs::path out = testing_support::freshTempDir("files_command_weight") / "out.png";
  const CommandOutput run = runFacial({"render", face.string(), "--weight", "AU26_JawDrop=1e38", "--out", out.string()});
  EXPECT_TRUE(failedInOneLine(run));
  EXPECT_EQ(run.err, "facial render: error: --weight 'AU26_JawDrop=1e38': weight 1e+38 is outside [-10, 10]\n");
  // An identity shape is a weight too, baked into the rest mesh.
  const CommandOutput shape = runFacial({"render", face.string(), "--shape", "custom_shape=-1e30", "--out", out.string()});
  EXPECT_TRUE(failedInOneLine(shape));
  EXPECT_NE(shape.err.find(": --shape 'custom_shape=-1e30': weight -1e+30 is outside [-10, 10]\n"), std::string::npos)
      << shape.err;
  EXPECT_FALSE(fs::exists(out));
}

// A name the user (or a file) gives is never echoed whole: 100 KB on the
// command line (close to Linux's limit for one argument), 10 MB inside a graph.
TEST(FilesCommand, LongNamesAreShortenedInTheErrorLine) {
  const fs::path dir = testing_support::freshTempDir("files_command_long_name");
  const std::string longModel = (dir / std::string(100000, 'm')).string() + ".glb";
  CommandOutput run = runFacial({"render", longModel, "--out", (dir / "out.png").string()});
  EXPECT_TRUE(failedInOneLine(run));
  EXPECT_LT(run.err.size(), 2 * app::kMaxNameInMessage) << run.err.substr(0, 1000);
  EXPECT_NE(run.err.find(" bytes)..."), std::string::npos) << run.err.substr(0, 1000);

  const fs::path face = writeTestFace("files_command_long_name_face");
  testing_support::writeFile(dir / "graph.json", R"({"version": 1, "channels": "actionUnits", "timelines": {"t": ")" +
                                                     std::string(10 << 20, 't') +
                                                     R"("}, "root": {"type": "timeline", "timeline": "t"}})");
  run = runFacial({"play", (dir / "graph.json").string(), "--model", face.string(), "--out", (dir / "frames").string()});
  EXPECT_TRUE(failedInOneLine(run));
  EXPECT_LT(run.err.size(), 3 * app::kMaxNameInMessage) << run.err.substr(0, 1000);
  EXPECT_NE(run.err.find("/timelines/t: timeline file 'ttt"), std::string::npos) << run.err.substr(0, 1000);
  EXPECT_TRUE(run.err.ends_with("ttt' not found\n")) << run.err.substr(0, 1000);
  EXPECT_FALSE(fs::exists(dir / "frames" / "frame_0000.png"));
}

// `play --out DIR` twice, the second run shorter: DIR holds the second run's
// frames only (and the user's own files), rendered headless with validation on.
TEST(FilesCommand, PlayReplacesTheFramesOfAnEarlierLongerRun) {
  const fs::path dir = testing_support::freshTempDir("files_command_play_frames");
  const fs::path face = writeTestFace("files_command_play_face");
  testing_support::writeFile(dir / "t.json", kTimeline);
  const fs::path frames = dir / "frames";
  testing_support::writeFile(frames / "notes.txt", "kept");
  for (const char* seconds : {"1", "0.5"}) {
    const CommandOutput run = runFacial({"play", (dir / "t.json").string(), "--model", face.string(), "--fps", "4",
                                         "--seconds", seconds, "--size", "32x32", "--out", frames.string()});
    ASSERT_TRUE(ranCleanly(run)) << run.err;
  }
  EXPECT_EQ(filesIn(frames), (std::set<std::string>{"frame_0000.png", "frame_0001.png", "notes.txt"}));

  // A graph naming a timeline outside its folder plays only when the user allows it.
  fs::create_directories(dir / "graphs");
  testing_support::writeFile(dir / "graphs" / "g.json", R"({"version": 1, "channels": "actionUnits",
    "timelines": {"t": "../t.json"}, "root": {"type": "timeline", "timeline": "t"}})");
  const std::vector<std::string> play = {"play", (dir / "graphs" / "g.json").string(), "--model", face.string(), "--fps", "4",
                                         "--seconds", "0.25", "--size", "32x32", "--out", frames.string()};
  CommandOutput run = runFacial(play);
  EXPECT_TRUE(failedInOneLine(run));
  EXPECT_NE(run.err.find("/timelines/t: '../t.json' points outside the folder of the file naming it"), std::string::npos) << run.err;
  std::vector<std::string> allowed = play;
  allowed.push_back("--allow-outside-paths");
  run = runFacial(allowed);
  EXPECT_TRUE(ranCleanly(run)) << run.err;
  EXPECT_EQ(filesIn(frames), (std::set<std::string>{"frame_0000.png", "notes.txt"}));
}

}  // namespace
}  // namespace cli_test::output_paths
