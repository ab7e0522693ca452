// The editor's autosave end to end: an editor edits a timeline and closes
// without saving; the next editor that opens the file recovers the edits and
// says so, while the file itself stays as it was until the user saves.
#include <chrono>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "editor/autosave.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

// A fresh folder with a copy of data/timelines/talk.json and edit.txt, a script
// that opens it and keys every track at 0.5 s (each action at its own time).
struct EditFolder {
  fs::path dir;
  std::string original;  // talk.json as copied
};

EditFolder folderEditingTalk(const std::string& name, const char* open, const char* seek, const char* key) {
  EditFolder folder{testing_support::freshTempDir(name), {}};
  fs::copy_file(testing_support::sourceDir() / "data" / "timelines" / "talk.json", folder.dir / "talk.json");
  folder.original = editor_test::readText(folder.dir / "talk.json");
  testing_support::writeFile(folder.dir / "edit.txt", std::string(open) + " timeline-open talk.json\n" + seek +
                                                          " timeline-seek 0.5\n" + key + " timeline-key-all\n");
  return folder;
}

TEST(EditorAutosave, TheNextEditorRecoversUnsavedTimelineEdits) {
  REQUIRE_XVFB();
  const auto [dir, original] = folderEditingTalk("editor_autosave", "0.2", "0.4", "0.5");
  const editor_test::EditorRun first = editor_test::runEditor(dir, "--script edit.txt", 2.0f);
  ASSERT_EQ(first.exitCode, 0) << first.log;
  EXPECT_TRUE(fs::exists(dir / editor::autosavePathFor("talk.json"))) << "the unsaved edits are kept:\n" << first.log;
  EXPECT_EQ(editor_test::readText(dir / "talk.json"), original) << "nothing was saved to the file";

  const editor_test::EditorRun second = editor_test::runEditor(dir, "--timeline talk.json", 1.0f);
  ASSERT_EQ(second.exitCode, 0) << second.log;
  EXPECT_NE(second.log.find("recovered unsaved edits of talk.json from .talk.json.autosave"), std::string::npos)
      << second.log;
  EXPECT_EQ(editor_test::readText(dir / "talk.json"), original) << "recovery does not write the file by itself";
}

// A device lost in the middle of editing (injected: lavapipe never loses one,
// see engine/vk/device/fault_injection.h). The editor writes the unsaved edits to the
// autosave and reports the loss in one line that says where they are, exits 1
// (no crash, no hang: long before --quit-after) without a validation message;
// the file itself is untouched and the autosave holds the edits for the next start.
TEST(EditorAutosave, LostDeviceKeepsTheUnsavedEditsAndSaysWhere) {
  REQUIRE_XVFB();
  const auto [dir, original] = folderEditingTalk("editor_device_lost", "0", "0", "0");
  // The script's actions all run in the first frame, so the loss at the third comes after them.
  ASSERT_EQ(::setenv("FACIAL_VK_FAULTS", "device-lost@3", 1), 0);
  const auto start = std::chrono::steady_clock::now();
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--script edit.txt --size 640x400", 60.0f);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ::unsetenv("FACIAL_VK_FAULTS");

  EXPECT_EQ(run.exitCode, 1) << run.log;
  EXPECT_LT(seconds, 45.0) << "the editor ended at the lost device, not at --quit-after:\n" << run.log;
  size_t errorLines = 0;
  std::istringstream lines(run.log);
  for (std::string line; std::getline(lines, line);)
    if (line.find("error:") != std::string::npos) ++errorLines;
  EXPECT_EQ(errorLines, 1u) << run.log;
  EXPECT_NE(run.log.find("the Vulkan device was lost (vkQueueSubmit failed: VK_ERROR_DEVICE_LOST)"), std::string::npos)
      << run.log;
  EXPECT_NE(run.log.find("; unsaved timeline edits are in .talk.json.autosave (the next start recovers them)\n"),
            std::string::npos)
      << run.log;
  EXPECT_NE(run.log.find("validation on"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("vulkan validation:"), std::string::npos) << run.log;

  EXPECT_EQ(editor_test::readText(dir / "talk.json"), original) << "nothing was saved to the file";
  auto recovered = editor::recoverAutosave(dir / "talk.json");
  ASSERT_TRUE(recovered) << recovered.error().message;
  ASSERT_TRUE(recovered->has_value()) << "the autosave holds the edits";
  EXPECT_TRUE((*recovered)->document.dirty());
  auto saved = editor::TimelineDocument::load(dir / "talk.json");
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_GT((*recovered)->document.toTimeline().keys.size(), saved->toTimeline().keys.size())
      << "the recovered clip has the keys added at 0.5 s";
}

}  // namespace
