// Killing the editor at any moment during a save leaves the old or the new
// file, never a mix: a child process saves two versions of a timeline in
// turn, as fast as it can, and is SIGKILLed at random moments; after every
// kill the file must be byte-for-byte one of the two versions.
//
// The same harness run over a plain (non-atomic) write must catch torn files:
// that shows the kills really land inside saves, so the atomic run is a test
// that can fail.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "editor/atomic_file.h"
#include "editor/timeline_document.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using editor::TimelineDocument;

// A clip big enough (tens of kB) that a save takes a while to write.
TimelineDocument bigClip(const std::string& name, float shift) {
  TimelineDocument doc(name, 10.0f);
  for (int t = 0; t < 40; ++t) {
    auto track = doc.addTrack("channel_" + std::to_string(t));
    EXPECT_TRUE(track.ok());
    for (int k = 0; k < 100; ++k) EXPECT_TRUE(doc.setKey(*track, 0.1f * float(k), 0.5f + 0.4f * std::sin(float(k + t) * shift)).ok());
  }
  return doc;
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct KillFigures {
  int rounds = 0;
  int sawOld = 0, sawNew = 0, torn = 0;
  int killedMidSave = 0;  // a temporary sibling was left behind: the kill landed inside a save
};

// Forks a child that calls save(a) and save(b) in turn for ever, sending a
// byte down a pipe as each save starts; after 1-3 starts, waits a random part
// of one save's measured length and kills it, then checks the file. Counting
// starts (not wall time from the fork) keeps the kills inside saves however
// slowly a loaded machine or a sanitizer runs the child. `path` holds version
// a at the start.
KillFigures killRepeatedly(const fs::path& path, const std::string& a, const std::string& b, int rounds,
                           const std::function<void(int version)>& save) {
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  for (int i = 0; i < 4; ++i) save(0);  // version a stays; times one save
  const auto saveTime = (Clock::now() - started) / 4;
  const int saveMicros = std::max<int>(
      1, int(std::chrono::duration_cast<std::chrono::microseconds>(saveTime).count()));

  KillFigures figures;
  std::mt19937 random(7);
  for (int round = 0; round < rounds; ++round) {
    fs::remove(editor::temporarySibling(path));  // so a sibling found after the kill is this round's
    int starts[2];
    if (pipe(starts) != 0) {
      ADD_FAILURE() << "pipe failed";
      break;
    }
    const pid_t child = fork();
    if (child == 0) {
      close(starts[0]);
      for (int i = 0;; ++i) {
        if (write(starts[1], "s", 1) != 1) _exit(4);
        save(i & 1);
      }
    }
    close(starts[1]);
    EXPECT_GT(child, 0) << "fork failed";
    if (child <= 0) {
      close(starts[0]);
      break;
    }
    const int waitStarts = std::uniform_int_distribution<int>(1, 3)(random);
    char byte = 0;
    for (int seen = 0; seen < waitStarts && read(starts[0], &byte, 1) == 1;) ++seen;
    std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, saveMicros)(random)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    close(starts[0]);
    ++figures.rounds;
    if (fs::exists(editor::temporarySibling(path))) ++figures.killedMidSave;
    const std::string content = readAll(path);
    if (content == a)
      ++figures.sawOld;
    else if (content == b)
      ++figures.sawNew;
    else
      ++figures.torn;
  }
  return figures;
}

// Two versions of one clip, each also saved alone to know its exact bytes;
// `path` starts with version a.
struct TwoVersions {
  explicit TwoVersions(const std::string& name)
      : dir(testing_support::freshTempDir(name)), path(dir / "clip.json"),
        first(bigClip("clip", 0.3f)), second(bigClip("clip", 0.7f)) {
    EXPECT_TRUE(first.save(dir / "a.json").ok());
    EXPECT_TRUE(second.save(dir / "b.json").ok());
    a = readAll(dir / "a.json");
    b = readAll(dir / "b.json");
    EXPECT_NE(a, b);
    std::ofstream(path, std::ios::binary) << a;
  }
  fs::path dir, path;
  TimelineDocument first, second;
  std::string a, b;
};

TEST(KillDuringSave, TimelineSaveLeavesTheOldOrTheNewFile) {
  TwoVersions v("kill_during_save");
  const fs::path& path = v.path;
  TimelineDocument &first = v.first, &second = v.second;
  const std::string &a = v.a, &b = v.b;

  const KillFigures f = killRepeatedly(path, a, b, 30, [&](int version) {
    auto saved = (version ? second : first).save(path);
    if (!saved) _exit(3);
  });
  EXPECT_EQ(f.torn, 0) << f.torn << " of " << f.rounds << " kills left a file that is neither version";
  EXPECT_EQ(f.sawOld + f.sawNew, f.rounds);
  // The kills must really have landed inside saves, else this proves nothing.
  EXPECT_GT(f.killedMidSave, 0) << "no kill interrupted a save";
  std::printf("kill during save: %d kills, %d mid-save, old %d, new %d, torn %d\n", f.rounds, f.killedMidSave,
              f.sawOld, f.sawNew, f.torn);

  // The next save after a kill replaces the leftover temporary sibling.
  ASSERT_TRUE(second.save(path).ok());
  EXPECT_EQ(readAll(path), b);
  EXPECT_FALSE(fs::exists(editor::temporarySibling(path)));
}

TEST(KillDuringSave, TheHarnessCatchesAPlainWrite) {
  TwoVersions v("kill_during_plain_write");
  const fs::path& path = v.path;
  const std::string &a = v.a, &b = v.b;

  // Written in place, in small pieces as a stream flushes: what the editor must not do.
  const KillFigures f = killRepeatedly(path, a, b, 20, [&](int version) {
    const std::string& text = version ? b : a;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    for (size_t at = 0; at < text.size(); at += 4096) out.write(text.data() + at, std::min<size_t>(4096, text.size() - at)).flush();
  });
  EXPECT_GT(f.torn, 0) << "the harness never caught a half-written file in " << f.rounds << " kills";
}

}  // namespace
