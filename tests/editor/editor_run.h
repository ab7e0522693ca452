#pragma once
// Running the built facial-editor under a virtual X server (xvfb-run) with
// validation on, and reading what it leaves behind: its log, its screenshots.
#include <cstdlib>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"

namespace editor_test {

inline bool onPath(const char* program) {
  return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0;
}

#define REQUIRE_XVFB()                                                                         \
  do {                                                                                         \
    if (!editor_test::onPath("xvfb-run"))                                                      \
      GTEST_SKIP() << "xvfb-run is not installed: the editor window cannot run headless";     \
  } while (0)

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct EditorRun {
  int exitCode = -1;
  std::string log;  // stdout + stderr
  eng::Image shot;  // the --screenshot frame
  bool shotRead = false;
};

// facial-editor ARGUMENTS --quit-after SECONDS --screenshot DIR/editor.png, run
// in `dir` (relative paths in a script land there) at 1280x800.
inline EditorRun runEditor(const std::filesystem::path& dir, const std::string& arguments, float seconds = 4.0f) {
  namespace fs = std::filesystem;
  EditorRun run;
  const fs::path program = fs::path(FACIAL_BINARY_DIR) / "bin" / "facial-editor";
  const fs::path shot = dir / "editor.png", log = dir / "editor.log", status = dir / "editor.status";
  // The program's own exit status goes to a file: xvfb-run's would replace it
  // with 5 when its clean-up of the temporary X authority fails.
  const std::string command = "cd '" + dir.string() + "' && FACIAL_VALIDATION=1 xvfb-run -a -s '-screen 0 1280x800x24' sh -c \"'" +
                              program.string() + "' " + arguments + " --quit-after " + std::to_string(seconds) +
                              " --screenshot '" + shot.string() + "' >'" + log.string() + "' 2>&1; echo \\$? >'" +
                              status.string() + "'\" >'" + (dir / "xvfb-run.log").string() + "' 2>&1";
  fs::remove(status);
  (void)std::system(command.c_str());
  if (const std::string code = readText(status); !code.empty()) run.exitCode = std::stoi(code);
  run.log = readText(log);
  if (run.exitCode == -1) run.log += "\n(no exit status; xvfb-run said:)\n" + readText(dir / "xvfb-run.log");
  if (auto image = eng::readImage(shot)) {
    run.shot = std::move(*image);
    run.shotRead = true;
  }
  return run;
}

// Validation active and silent, and a 1280x800 last frame (the exit code is the caller's to check).
inline ::testing::AssertionResult validationSilent(const EditorRun& run) {
  if (run.log.find("validation on") == std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation was not active:\n" << run.log;
  if (run.log.find("vulkan validation:") != std::string::npos)
    return ::testing::AssertionFailure() << "Vulkan validation messages:\n" << run.log;
  if (!run.shotRead) return ::testing::AssertionFailure() << "no screenshot:\n" << run.log;
  if (run.shot.width != 1280 || run.shot.height != 800)
    return ::testing::AssertionFailure() << "screenshot is " << run.shot.width << "x" << run.shot.height;
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult ranCleanly(const EditorRun& run) {
  if (run.exitCode != 0) return ::testing::AssertionFailure() << "exit code " << run.exitCode << ":\n" << run.log;
  return validationSilent(run);
}

// `script` written to DIR/NAME and refused before any window opens (no
// display): expects exit status 1 and returns what the program said.
inline std::string scriptRefusal(const std::filesystem::path& dir, const std::string& name, const std::string& script) {
  const std::filesystem::path program = std::filesystem::path(FACIAL_BINARY_DIR) / "bin" / "facial-editor";
  testing_support::writeFile(dir / name, script);
  const std::string command = "cd '" + dir.string() + "' && DISPLAY= '" + program.string() + "' --script " + name + " >log.txt 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 1) << script;
  return readText(dir / "log.txt");
}

// Issue 34's keying, as a script's first lines (0.2 to 0.8 s): neutral ->
// happy -> surprise keyed at 0, 1, 2 s with cosine easing, the last two keys
// of every track box-selected and moved to 0.8 s and 1.8 s, copied, pasted at
// 2.5 s (the clip grows to 3.5 s).
inline const std::string kKeyEmotionsMoveAndPaste =
    "0.2 timeline-key-emotion neutral 0 cosine\n"
    "0.3 timeline-key-emotion happy 1 cosine\n"
    "0.4 timeline-key-emotion surprise 2 cosine\n"
    "0.5 timeline-box-select 0.9 2.1          # the last two keys of every track\n"
    "0.6 timeline-move-selected -0.2 0        # to 0.8 s and 1.8 s\n"
    "0.7 timeline-copy\n"
    "0.8 timeline-paste 2.5                   # 2.5 s and 3.5 s: the clip grows to 3.5 s\n";

inline glm::ivec3 pixel(const eng::Image& image, int x, int y) {
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 4;
  return {image.rgba8[i], image.rgba8[i + 1], image.rgba8[i + 2]};
}

inline int colourDistance(glm::ivec3 a, glm::ivec3 b) {
  return std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z);
}

// Mean colour distance (sum over R, G, B) of two same-sized images over [x0,x1) x [y0,y1).
inline double meanDifference(const eng::Image& a, const eng::Image& b, int x0, int y0, int x1, int y1) {
  double sum = 0;
  size_t total = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++total) sum += colourDistance(pixel(a, x, y), pixel(b, x, y));
  return sum / double(std::max<size_t>(total, 1));
}

}  // namespace editor_test
