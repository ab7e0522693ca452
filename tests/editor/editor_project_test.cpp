// Projects end to end under xvfb-run: a scripted session edits a clip, sculpts
// and bakes, turns the view and saves the project; the next editor opens it
// with everything back (the same face on screen); a session killed with
// unsaved changes leaves them for the next one to recover; Export .glb writes
// what `facial play` renders.
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "editor/autosave.h"
#include "editor/project.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;
using editor_test::runEditor;

const std::string kSculptSmirk =
    "0.2 sculpt-landmark nose_root\n"
    "0.2 sculpt-landmark chin\n"
    "0.2 sculpt-landmark cheek_L\n"
    "0.3 sculpt-falloff 0.05\n"
    "0.3 sculpt-move 0.004 0.004 0\n"
    "0.4 sculpt-bake smirk\n";

// A fresh folder with a copy of talk.json; the editors started from here keep
// their recent projects list in it (XDG_CONFIG_HOME), not in the user's.
fs::path folderWithTalk(const std::string& name) {
  const fs::path dir = testing_support::freshTempDir(name);
  fs::copy_file(testing_support::sourceDir() / "data" / "timelines" / "talk.json", dir / "talk.json");
  setenv("XDG_CONFIG_HOME", (dir / "config").c_str(), 1);
  return dir;
}

// Share of the viewport's pixels (between the side panels, under the status
// lines, above the timeline) that differ clearly: the control point markers
// of the session that baked are a few dozen pixels, another view or face is most of them.
double changedShare(const eng::Image& a, const eng::Image& b) {
  size_t changed = 0, total = 0;
  for (int y = 60; y < 520; ++y)
    for (int x = 330; x < 950; ++x, ++total)
      changed += editor_test::colourDistance(editor_test::pixel(a, x, y), editor_test::pixel(b, x, y)) > 24;
  return double(changed) / double(total);
}

// A session that makes a project: talk.json edited, a smirk baked, the view turned, saved as anim.json.
editor_test::EditorRun makeProject(const fs::path& dir) {
  testing_support::writeFile(dir / "make.txt", kSculptSmirk +
                                                   "0.5 timeline-open talk.json\n"
                                                   "0.6 timeline-seek 0.5\n"
                                                   "0.7 timeline-key AU26_JawDrop\n"
                                                   "0.8 orbit 25 -8\n"
                                                   "0.9 timeline-seek 0.4\n"
                                                   "1.0 screenshot before.png\n"
                                                   "1.1 project-save-as anim.json\n"
                                                   "1.2 quit\n");
  return runEditor(dir, "--script make.txt", 20.0f);
}

TEST(EditorProject, SavedSessionComesBackWhenTheProjectIsOpened) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_session");
  // One fixed render scale (not the dynamic resolution, which follows each run's frame times), so frames compare.
  setenv("FACIAL_RENDER_SCALE", "1", 1);
  const editor_test::EditorRun made = makeProject(dir);
  ASSERT_TRUE(editor_test::ranCleanly(made));
  EXPECT_NE(made.log.find("saved project anim.json"), std::string::npos) << made.log;
  auto project = editor::loadProject(dir / "anim.json");
  ASSERT_TRUE(project) << project.error().message;
  ASSERT_EQ(project->clips.size(), 1u);
  EXPECT_TRUE(fs::exists(project->clips[0].file)) << project->clips[0].file;
  ASSERT_EQ(project->sculptTargets.size(), 1u);
  EXPECT_EQ(project->sculptTargets[0].name, "smirk");
  EXPECT_TRUE(fs::exists(dir / "anim.sculpt.glb"));
  EXPECT_NEAR(project->view.yawDegrees, 25.0f, 1e-3f);
  EXPECT_NEAR(project->view.pitchDegrees, -8.0f, 1e-3f);
  EXPECT_FALSE(fs::exists(editor::projectAutosavePath(dir / "anim.json"))) << "saved: no autosave left";
  EXPECT_FALSE(fs::exists(dir / ".timeline.json.autosave")) << "the clip was saved with the project";
  editor::RecentProjects recent(dir / "config" / "facial" / "recent.json");
  ASSERT_TRUE(recent.load());
  ASSERT_FALSE(recent.paths().empty());
  EXPECT_TRUE(fs::equivalent(recent.paths()[0], dir / "anim.json")) << recent.paths()[0];

  // The next editor, started on the project, shows the same face at the same time.
  testing_support::writeFile(dir / "reopen.txt",
                             "0.5 timeline-seek 0.4\n"
                             "0.6 screenshot after.png\n"
                             "0.7 quit\n");
  const editor_test::EditorRun reopened = runEditor(dir, "--project anim.json --script reopen.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(reopened));
  EXPECT_NE(reopened.log.find("opened project anim.json"), std::string::npos) << reopened.log;
  auto before = eng::readImage(dir / "before.png"), after = eng::readImage(dir / "after.png");
  ASSERT_TRUE(before && after);
  EXPECT_LT(changedShare(*before, *after), 0.01) << "the reopened project shows another face";
  // The check can fail: a plain editor at that time (no project: another view, no smirk) differs.
  testing_support::writeFile(dir / "plain.txt", "0.5 timeline-open talk.json\n0.6 timeline-seek 0.4\n0.7 screenshot plain.png\n0.8 quit\n");
  ASSERT_TRUE(editor_test::ranCleanly(runEditor(dir, "--script plain.txt", 20.0f)));
  auto plain = eng::readImage(dir / "plain.png");
  ASSERT_TRUE(plain);
  EXPECT_GT(changedShare(*before, *plain), 0.05);

  // And opened from inside an editor (File > Open), after New emptied it.
  testing_support::writeFile(dir / "open.txt",
                             "0.4 project-new\n"
                             "0.5 project-open anim.json\n"
                             "0.6 timeline-seek 0.4\n"
                             "0.7 screenshot opened.png\n"
                             "0.8 quit\n");
  const editor_test::EditorRun opened = runEditor(dir, "--script open.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(opened));
  auto inside = eng::readImage(dir / "opened.png");
  ASSERT_TRUE(inside);
  EXPECT_LT(changedShare(*before, *inside), 0.01);
  unsetenv("FACIAL_RENDER_SCALE");
}

TEST(EditorProject, UnsavedChangesOfAKilledEditorAreRecovered) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_crash");
  ASSERT_TRUE(editor_test::ranCleanly(makeProject(dir)));
  const std::string saved = editor_test::readText(dir / "anim.json");

  // An editor bakes a second expression and is killed before it saves.
  testing_support::writeFile(dir / "crash.txt",
                             "0.2 sculpt-landmark nose_root\n"
                             "0.2 sculpt-landmark chin\n"
                             "0.3 sculpt-move 0 -0.004 0\n"
                             "0.4 sculpt-bake frown\n");
  const fs::path program = testing_support::binaryDir() / "bin" / "facial-editor";
  const std::string command = "cd '" + dir.string() + "' && FACIAL_VALIDATION=1 xvfb-run -a -s '-screen 0 1280x800x24' sh -c \"'" +
                              program.string() + "' --project anim.json --script crash.txt --quit-after 120 >crash.log 2>&1 & " +
                              "echo \\$! > editor.pid; wait\" >/dev/null 2>&1 &";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const fs::path autosave = editor::projectAutosavePath(dir / "anim.json");
  for (int i = 0; i < 600 && !fs::exists(autosave); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_TRUE(fs::exists(autosave)) << editor_test::readText(dir / "crash.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the write is whole (renamed into place) already
  const int pid = std::atoi(editor_test::readText(dir / "editor.pid").c_str());
  ASSERT_GT(pid, 0);
  ::kill(pid, SIGKILL);
  for (int i = 0; i < 100 && ::kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(editor_test::readText(dir / "anim.json"), saved) << "the project file is untouched until a save";

  testing_support::writeFile(dir / "recover.txt", "0.5 project-save\n0.6 quit\n");
  const editor_test::EditorRun next = runEditor(dir, "--project anim.json --script recover.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(next));
  EXPECT_NE(next.log.find("recovered unsaved edits of anim.json"), std::string::npos) << next.log;
  auto project = editor::loadProject(dir / "anim.json");
  ASSERT_TRUE(project) << project.error().message;
  ASSERT_EQ(project->sculptTargets.size(), 2u) << "saving the recovered project keeps the frown";
  EXPECT_EQ(project->sculptTargets[1].name, "frown");
  auto sculpted = eng::loadModel(dir / "anim.sculpt.glb");
  ASSERT_TRUE(sculpted) << sculpted.error().message;
  EXPECT_FALSE(fs::exists(autosave));
}

TEST(EditorProject, QuitWithUnsavedChangesSavesOrDiscardsWithoutHanging) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_quit");
  ASSERT_TRUE(editor_test::ranCleanly(makeProject(dir)));
  testing_support::writeFile(dir / "discard.txt", "0.3 orbit 10 0\n0.4 timeline-seek 0.2\n0.5 timeline-key-all\n0.6 quit-discard\n");
  const editor_test::EditorRun discarded = runEditor(dir, "--project anim.json --script discard.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(discarded));
  EXPECT_FALSE(fs::exists(editor::projectAutosavePath(dir / "anim.json")));
  EXPECT_FALSE(fs::exists(editor::autosavePathFor(dir / "anim.clips" / "talk.json"))) << "the clip's edits went too";

  testing_support::writeFile(dir / "save.txt", "0.4 timeline-seek 0.2\n0.5 timeline-key-all\n0.6 quit-save\n");
  const std::string clipBefore = editor_test::readText(dir / "anim.clips" / "talk.json");
  const editor_test::EditorRun saved = runEditor(dir, "--project anim.json --script save.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(saved));
  EXPECT_NE(editor_test::readText(dir / "anim.clips" / "talk.json"), clipBefore) << "quit-save wrote the clip";

  // An untitled project has no file to save to: the quit still happens, with one error line.
  testing_support::writeFile(dir / "untitled.txt", "0.3 sculpt-landmark chin\n0.3 sculpt-move 0 0.003 0\n0.4 sculpt-bake lift\n0.5 quit-save\n");
  const editor_test::EditorRun untitled = runEditor(dir, "--script untitled.txt", 20.0f);
  EXPECT_EQ(untitled.exitCode, 1) << untitled.log;
  EXPECT_NE(untitled.log.find("Save: the project has no file yet (use Save As)"), std::string::npos) << untitled.log;
  EXPECT_EQ(untitled.log.find("closed before"), std::string::npos) << untitled.log;
}

TEST(EditorProject, AProjectOnAnotherFaceOpensInANewEditorAndTheScriptGoesOn) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_other_face");
  fs::copy_file(testing_support::sourceDir() / "data" / "head.glb", dir / "other.glb");
  testing_support::writeFile(dir / "make.txt", "0.3 orbit 30 0\n0.4 project-save-as other.json\n0.5 quit\n");
  ASSERT_TRUE(editor_test::ranCleanly(runEditor(dir, "--model other.glb --script make.txt", 20.0f)));
  testing_support::writeFile(dir / "open.txt", "0.3 project-open other.json\n0.5 screenshot opened.png\n0.6 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script open.txt", 30.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  EXPECT_NE(run.log.find("other.json was made on another face: reopening the editor on it"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("opened project other.json"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("facial-editor: other,"), std::string::npos) << "the second editor runs the project's face:\n" << run.log;
  EXPECT_TRUE(fs::exists(dir / "opened.png")) << "the script went on in the new editor";
}

TEST(EditorProject, BrokenProjectIsOneLineNamingTheFile) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_broken_open");
  testing_support::writeFile(dir / "bad.json", "{\"version\": 1, \"view\": {\"zoom\": -1}}");
  testing_support::writeFile(dir / "open.txt", "0.3 project-open bad.json\n0.4 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script open.txt", 20.0f);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.log.find("error: bad.json: /view: zoom -1 must be > 0"), std::string::npos) << run.log;
  // The new actions' arguments are checked before the window opens, like every action's.
  testing_support::writeFile(dir / "args.txt", "0.1 project-save-as\n");
  const editor_test::EditorRun args = runEditor(dir, "--script args.txt", 5.0f);
  EXPECT_EQ(args.exitCode, 1);
  EXPECT_NE(args.log.find("args.txt:1: 'project-save-as' takes 1 argument(s), got 0"), std::string::npos) << args.log;
  testing_support::writeFile(dir / "args.txt", "0.1 export-gif a.gif talk extra\n");
  EXPECT_NE(runEditor(dir, "--script args.txt", 5.0f).log.find("'export-gif' takes 1 or 2 argument(s), got 3"), std::string::npos);
  const editor_test::EditorRun start = runEditor(dir, "--project bad.json", 5.0f);
  EXPECT_EQ(start.exitCode, 1);
  EXPECT_NE(start.log.find("facial-editor: error: bad.json: /view: zoom -1 must be > 0"), std::string::npos) << start.log;
}

TEST(EditorProject, ExportedGlbPlaysInFacialPlay) {
  REQUIRE_XVFB();
  const fs::path dir = folderWithTalk("editor_project_export");
  testing_support::writeFile(dir / "export.txt", kSculptSmirk +
                                                     "0.5 timeline-open talk.json\n"
                                                     "0.6 export-glb out.glb\n"
                                                     "0.7 export-gif talk.gif\n"
                                                     "0.8 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script export.txt", 30.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));
  EXPECT_NE(run.log.find("exported out.glb: the face with 1 sculpted target(s) and 1 clip(s)"), std::string::npos) << run.log;
  EXPECT_GT(fs::file_size(dir / "talk.gif"), 1000u);
  auto model = eng::loadModel(dir / "out.glb");
  ASSERT_TRUE(model) << model.error().message;
  bool smirk = false;
  for (const eng::Mesh& mesh : model->meshes) smirk = smirk || std::find(mesh.targetNames.begin(), mesh.targetNames.end(), "smirk") != mesh.targetNames.end();
  EXPECT_TRUE(smirk) << "the sculpted target is in the glb";

  // What another program sees: the animation as a timeline, played on the exported face.
  const fs::path facial = testing_support::binaryDir() / "bin" / "facial";
  const std::string play = "cd '" + dir.string() + "' && FACIAL_VALIDATION=1 '" + facial.string() +
                           "' timeline import out.glb --animation talk --out played.json >play.log 2>&1 && FACIAL_VALIDATION=1 '" +
                           facial.string() + "' play played.json --model out.glb --fps 10 --size 256x256 --out frames >>play.log 2>&1";
  ASSERT_EQ(std::system(play.c_str()), 0) << editor_test::readText(dir / "play.log");
  auto first = eng::readImage(dir / "frames" / "frame_0000.png"), middle = eng::readImage(dir / "frames" / "frame_0005.png");
  ASSERT_TRUE(first && middle) << editor_test::readText(dir / "play.log");
  EXPECT_GT(editor_test::meanDifference(*first, *middle, 64, 128, 192, 256), 0.5) << "the mouth moves in the played animation";
}

}  // namespace
