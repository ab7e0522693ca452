// The editor's autosave end to end: an editor edits a timeline and closes
// without saving; the next editor that opens the file recovers the edits and
// says so, while the file itself stays as it was until the user saves.
#include <gtest/gtest.h>

#include "editor/autosave.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

TEST(EditorAutosave, TheNextEditorRecoversUnsavedTimelineEdits) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_autosave");
  fs::copy_file(testing_support::sourceDir() / "data" / "timelines" / "talk.json", dir / "talk.json");
  const std::string original = editor_test::readText(dir / "talk.json");
  testing_support::writeFile(dir / "edit.txt",
                             "0.2 timeline-open talk.json\n"
                             "0.4 timeline-seek 0.5\n"
                             "0.5 timeline-key-all\n");
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

}  // namespace
