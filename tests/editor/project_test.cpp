// The editor's project file (editor/project.h): what is saved comes back,
// paths follow the project's folder, broken files are refused with one line
// naming the file and the problem, and the recent list keeps the newest first.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "editor/autosave.h"
#include "editor/project.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

editor::Project sampleProject(const fs::path& dir) {
  editor::Project p;
  p.model = dir / "faces" / "anna.glb";
  p.graph = dir / "graphs" / "anna.json";
  editor::TimelineSettings settings{.frameRate = 24.0f, .muted = {"AU12"}, .solo = {"happy", "sad"}};
  settings.playback = {.hasLoopRange = true, .loopStart = 0.5f, .loopEnd = 1.5f, .speed = 0.5f};
  p.clips = {{"hello", editor::projectClipPath(dir / "anna.json", "hello"), settings}};
  p.sculptModel = editor::projectSculptPath(dir / "anna.json");
  p.sculptTargets = {{"smirk", 0.75f}, {"frown", 1.0f}};
  p.view = {.yawDegrees = 20.0f, .pitchDegrees = -5.0f, .zoom = 1.5f, .wholeModel = true};
  return p;
}

TEST(EditorProject, SavedProjectComesBack) {
  const fs::path dir = testing_support::freshTempDir("editor_project_round_trip");
  const editor::Project saved = sampleProject(dir);
  ASSERT_TRUE(editor::saveProject(saved, dir / "anna.json"));
  auto loaded = editor::loadProject(dir / "anna.json");
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->model, saved.model);
  EXPECT_TRUE(loaded->rigmap.empty());
  EXPECT_EQ(loaded->graph, saved.graph);
  ASSERT_EQ(loaded->clips.size(), 1u);
  EXPECT_EQ(loaded->clips[0].name, "hello");
  EXPECT_EQ(loaded->clips[0].file, dir / "anna.clips" / "hello.json");
  EXPECT_EQ(loaded->clips[0].settings, saved.clips[0].settings) << "the dope sheet's frame rate, loop range, speed, mute / solo";
  EXPECT_EQ(loaded->sculptModel, dir / "anna.sculpt.glb");
  ASSERT_EQ(loaded->sculptTargets.size(), 2u);
  EXPECT_EQ(loaded->sculptTargets[0].name, "smirk");
  EXPECT_FLOAT_EQ(loaded->sculptTargets[0].weight, 0.75f);
  EXPECT_EQ(loaded->view, saved.view);
}

TEST(EditorProject, PathsAreRelativeSoTheProjectMovesWithItsFiles) {
  const fs::path dir = testing_support::freshTempDir("editor_project_moves");
  fs::create_directories(dir / "a");
  ASSERT_TRUE(editor::saveProject(sampleProject(dir / "a"), dir / "a" / "anna.json"));
  const std::string text = editor_test::readText(dir / "a" / "anna.json");
  EXPECT_NE(text.find("\"faces/anna.glb\""), std::string::npos) << text;
  fs::rename(dir / "a", dir / "b");
  auto loaded = editor::loadProject(dir / "b" / "anna.json");
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->model, dir / "b" / "faces" / "anna.glb");
}

TEST(EditorProject, ClipFileNamesAreSafe) {
  EXPECT_EQ(editor::projectClipPath("p/x.json", "a b/../c"), fs::path("p/x.clips/a_b____c.json"));
  EXPECT_EQ(editor::projectClipPath("p/x.json", ""), fs::path("p/x.clips/clip.json"));
}

TEST(EditorProject, BrokenProjectsNameTheFileAndTheProblem) {
  const fs::path dir = testing_support::freshTempDir("editor_project_broken");
  const auto problem = [&](const std::string& text) {
    testing_support::writeFile(dir / "p.json", text);
    auto loaded = editor::loadProject(dir / "p.json");
    EXPECT_FALSE(loaded) << text;
    return loaded ? std::string() : loaded.error().message;
  };
  const std::string file = (dir / "p.json").string();
  EXPECT_EQ(problem("{\"version\": 1, \"view\": {\"zoom\": \"big\"}}").rfind(file + ": /view/zoom: ", 0), 0u);
  EXPECT_NE(problem("{\"version\": 2}").find("newer release"), std::string::npos);
  EXPECT_NE(problem("{\"version\": 1, \"clips\": [{\"name\": \"a\"}]}").find("/clips/0"), std::string::npos);
  EXPECT_NE(problem("{\"version\": 1, \"modle\": \"x\"}").find("modle"), std::string::npos);
  EXPECT_NE(problem("{\"version\": 1, \"view\": {\"zoom\": 0}}").find("must be > 0"), std::string::npos);
  EXPECT_NE(problem("{\"version\": 1, \"sculpt\": {\"targets\": [{\"name\": \"s\"}]}}").find("no \"file\""),
            std::string::npos);
  EXPECT_NE(problem("{\"version\": 1,").find(file), std::string::npos);
  const std::string clip = "{\"version\": 1, \"clips\": [{\"name\": \"a\", \"file\": \"a.json\", \"settings\": ";
  EXPECT_NE(problem(clip + "{\"fps\": 0}}]}").find("/clips/0/settings: fps 0 must be 1 to 1000"), std::string::npos);
  EXPECT_NE(problem(clip + "{\"loop\": [2, 1]}}]}").find("/clips/0/settings/loop: loop range"), std::string::npos);
  EXPECT_NE(problem(clip + "{\"muted\": [1]}}]}").find("/clips/0/settings/muted/0"), std::string::npos);
  auto missing = editor::loadProject(dir / "none.json");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, eng::ErrorKind::NotFound);
}

TEST(EditorProject, RecentListKeepsTheNewestFirstWithoutRepeats) {
  const fs::path dir = testing_support::freshTempDir("editor_project_recent");
  editor::RecentProjects recent(dir / "config" / "facial" / "recent.json");
  ASSERT_TRUE(recent.load()) << "a missing list is an empty list";
  for (int i = 0; i < 12; ++i) ASSERT_TRUE(recent.add(dir / ("p" + std::to_string(i) + ".json")));
  ASSERT_TRUE(recent.add(dir / "p5.json"));
  editor::RecentProjects reread(recent.file());
  ASSERT_TRUE(reread.load());
  ASSERT_EQ(reread.paths().size(), editor::RecentProjects::kMax);
  EXPECT_EQ(reread.paths()[0], dir / "p5.json");
  EXPECT_EQ(reread.paths()[1], dir / "p11.json");
  EXPECT_EQ(std::count(reread.paths().begin(), reread.paths().end(), dir / "p5.json"), 1);

  testing_support::writeFile(recent.file(), "{\"projects\": [3]}");
  auto broken = reread.load();
  ASSERT_FALSE(broken);
  EXPECT_EQ(broken.error().message.rfind(recent.file().string() + ": /projects/0", 0), 0u) << broken.error().message;
  EXPECT_TRUE(reread.paths().empty());
}

TEST(EditorProject, RecentListLivesUnderXdgConfigHome) {
  const char* old = std::getenv("XDG_CONFIG_HOME");
  const std::string kept = old ? old : "";
  setenv("XDG_CONFIG_HOME", "/tmp/cfg", 1);
  EXPECT_EQ(editor::RecentProjects::defaultFile(), fs::path("/tmp/cfg/facial/recent.json"));
  if (old) setenv("XDG_CONFIG_HOME", kept.c_str(), 1);
  else unsetenv("XDG_CONFIG_HOME");
}

TEST(EditorProject, AutosaveNewerThanTheProjectIsRecovered) {
  const fs::path dir = testing_support::freshTempDir("editor_project_recover");
  const fs::path project = dir / "anna.json";
  editor::Project saved = sampleProject(dir);
  ASSERT_TRUE(editor::saveProject(saved, project));
  auto none = editor::recoverProjectAutosave(project);
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->has_value());

  // An editor autosaved a newer state, then died.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // file times must differ
  editor::Project edited = saved;
  edited.sculptTargets.push_back({"smile", 0.5f});
  edited.sculptModel = editor::projectSculptAutosavePath(project);
  ASSERT_TRUE(editor::saveProject(edited, editor::projectAutosavePath(project)));
  auto recovered = editor::recoverProjectAutosave(project);
  ASSERT_TRUE(recovered) << recovered.error().message;
  ASSERT_TRUE(recovered->has_value());
  EXPECT_EQ((*recovered)->project.sculptTargets.size(), 3u);
  EXPECT_EQ((*recovered)->project.sculptModel, editor::projectSculptAutosavePath(project));
  EXPECT_EQ((*recovered)->project.model, saved.model) << "relative paths read as the project's own";
  EXPECT_NE((*recovered)->message.find("recovered unsaved edits of " + project.string()), std::string::npos);

  // Saving the project makes the autosave stale: it is removed, not recovered.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(editor::saveProject(saved, project));
  auto stale = editor::recoverProjectAutosave(project);
  ASSERT_TRUE(stale);
  EXPECT_FALSE(stale->has_value());
  EXPECT_FALSE(fs::exists(editor::projectAutosavePath(project)));

  testing_support::writeFile(editor::projectAutosavePath(project), "{");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  fs::last_write_time(editor::projectAutosavePath(project), fs::file_time_type::clock::now());
  auto broken = editor::recoverProjectAutosave(project);
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().message.find(editor::projectAutosavePath(project).string()), std::string::npos);
}

}  // namespace
