// facial-editor under a virtual X server (xvfb-run): starts the built program
// for a few seconds with --quit-after / --screenshot and checks the last
// frame (face in the middle, the four panels drawn around it) and that the
// validation layer stayed silent.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app/face_setup.h"
#include "tests/common/study_obj_set.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;
using editor_test::pixel;
using editor_test::ranCleanly;
using editor_test::runEditor;

int distance(glm::ivec3 a, glm::ivec3 b) { return editor_test::colourDistance(a, b); }

// Fraction of pixels in [x0,x1) x [y0,y1) that differ from `reference` by more than 60.
double differingFraction(const eng::Image& image, int x0, int y0, int x1, int y1, glm::ivec3 reference) {
  size_t differ = 0, total = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++total)
      if (distance(pixel(image, x, y), reference) > 60) ++differ;
  return double(differ) / double(std::max<size_t>(total, 1));
}

// The same against the viewport backdrop, a vertical gradient: each row is
// compared with its own colour at the viewport's right edge (x = 955).
double nonBackdropFraction(const eng::Image& image, int x0, int y0, int x1, int y1) {
  size_t differ = 0, total = 0;
  for (int y = y0; y < y1; ++y) {
    const glm::ivec3 backdrop = pixel(image, 955, y);
    for (int x = x0; x < x1; ++x, ++total)
      if (distance(pixel(image, x, y), backdrop) > 40) ++differ;
  }
  return double(differ) / double(std::max<size_t>(total, 1));
}

// Fraction of dark pixels (ImGui's window background; the lit backdrop has none).
double darkFraction(const eng::Image& image, int x0, int y0, int x1, int y1) {
  size_t dark = 0, total = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++total) {
      const glm::ivec3 p = pixel(image, x, y);
      if (p.x + p.y + p.z < 3 * 80) ++dark;
    }
  return double(dark) / double(std::max<size_t>(total, 1));
}

// The layout at 1280x800: columns of 320 px, a 240 px timeline strip.
void expectFaceAndPanels(const eng::Image& shot) {
  // Viewport (x 320..960, y 0..560): the backdrop's colour just inside its top-right corner.
  const double face = nonBackdropFraction(shot, 420, 60, 860, 520);
  EXPECT_GT(face, 0.25) << "the face fills the middle of the viewport";
  // The face is centred: its left and right halves both hold face pixels.
  EXPECT_GT(nonBackdropFraction(shot, 420, 150, 640, 450), 0.3);
  EXPECT_GT(nonBackdropFraction(shot, 640, 150, 860, 450), 0.3);
  // ...and it does not run under the panels: the viewport edges show backdrop.
  EXPECT_LT(nonBackdropFraction(shot, 330, 100, 360, 500), 0.05) << "face clipped by the left panels";
  EXPECT_LT(nonBackdropFraction(shot, 920, 100, 950, 500), 0.05) << "face clipped by the right panel";
  // The viewport edges are backdrop, not panel.
  EXPECT_LT(darkFraction(shot, 330, 100, 360, 500), 0.01);
  EXPECT_LT(darkFraction(shot, 920, 100, 950, 500), 0.01);
  // Panels: ImGui's dark window backgrounds with text, in all four places.
  for (const auto& [name, x0, y0, x1, y1] : {std::tuple{"state machine", 0, 20, 320, 270}, std::tuple{"control map", 0, 300, 320, 540},
                                            std::tuple{"sculpt", 960, 20, 1280, 540}, std::tuple{"timeline", 0, 580, 1280, 800}}) {
    EXPECT_GT(darkFraction(shot, x0, y0, x1, y1), 0.3) << name << " panel background";
    EXPECT_GT(differingFraction(shot, x0, y0, x1, y1, pixel(shot, x0 + 3, y1 - 3)), 0.02) << name << " panel has content";
  }
}

TEST(EditorWindow, BuiltInHeadWithAllPanels) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_window_head");
  const fs::path timeline = testing_support::sourceDir() / "data" / "timelines" / "talk.json";
  const editor_test::EditorRun run = runEditor(dir, "--trigger happy --timeline '" + timeline.string() + "'");
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_NE(run.log.find("state happy"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("3 timeline tracks"), std::string::npos) << run.log;
  expectFaceAndPanels(run.shot);
  // The timeline's keys (white diamonds) are drawn in its rows.
  EXPECT_GT(differingFraction(run.shot, 180, 680, 1270, 790, pixel(run.shot, 1275, 795)), 0.01);
}

TEST(EditorWindow, ArkitFaceFromShared) {
  FACIAL_REQUIRE_SHARED();
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_window_facecap");
  const editor_test::EditorRun run = runEditor(dir, "--model '" + (testing_support::sharedDir() / "assets" / "facecap.glb").string() + "' --trigger surprise");
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_NE(run.log.find("ARKit"), std::string::npos) << run.log;
  expectFaceAndPanels(run.shot);
}

// The study's hand-over (one OBJ per expression under artist names, converted
// with `facial convert`) opens in the editor through a rig map, and the state
// machine's triggers reach its emotion targets.
TEST(EditorWindow, ConvertedObjExpressionSetPlaysThroughARigMap) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_window_obj_set");
  auto head = app::FaceSetup::load({.model = testing_support::sourceDir() / "data" / "head.glb"});
  ASSERT_TRUE(head) << head.error().message;
  testing_support::writeStudyObjSet(
      head->model(), head->weightCount(),
      [&](const char* name, std::vector<float>& weights) {
        auto preset = head->findExpression(name);
        if (!preset) ADD_FAILURE() << preset.error().message;
        return preset && head->expressionWeights(**preset, 1.0f, weights).ok();
      },
      dir / "set");
  testing_support::writeFile(dir / "map.json", testing_support::studyRigMapJson(1.0f));
  const std::string convert = "'" + (fs::path(FACIAL_BINARY_DIR) / "bin" / "facial").string() + "' convert '" +
                              (dir / "set").string() + "' --out '" + (dir / "study.glb").string() + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(convert.c_str()), 0);

  const std::string face = "--model '" + (dir / "study.glb").string() + "' --rigmap '" + (dir / "map.json").string() + "'";
  const editor_test::EditorRun neutral = runEditor(dir, face + " --trigger neutral", 3.0f);
  ASSERT_TRUE(ranCleanly(neutral));
  const editor_test::EditorRun anger = runEditor(dir, face + " --trigger anger", 3.0f);
  ASSERT_TRUE(ranCleanly(anger));
  EXPECT_NE(anger.log.find("study, face from state machine, state anger"), std::string::npos) << anger.log;
  expectFaceAndPanels(anger.shot);
  // The scowl target moved the face (the view's middle), not the panels around it.
  size_t changed = 0, total = 0;
  for (int y = 60; y < 520; ++y)
    for (int x = 420; x < 860; ++x, ++total) changed += distance(pixel(anger.shot, x, y), pixel(neutral.shot, x, y)) > 24;
  EXPECT_GT(double(changed) / double(total), 0.01) << "anger on the converted set differs from neutral";
}

TEST(EditorWindow, ABrokenTimelineIsAnErrorNamingTheFile) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_window_broken");
  testing_support::writeFile(dir / "broken.json", "{\"version\": 1, \"tracks\": 7}");
  const editor_test::EditorRun run = runEditor(dir, "--timeline '" + (dir / "broken.json").string() + "'");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.log.find("broken.json"), std::string::npos) << run.log;
}

}  // namespace
