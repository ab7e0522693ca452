// The editor's landmarks (issue 33) through --script under xvfb-run: a face
// rigged on the fly (the visemes-only Ready Player Me avatar, with the
// landmarks file beside it, so no detector runs; upright, and lying as a
// Z-up export holds it), its 68 points shown, one dragged, the transfer run
// again and the points saved beside the face.
#include <filesystem>
#include <regex>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "autorig/face_landmarks.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;

// The avatar as its file holds it, turned by `turn` at its roots (identity:
// as shared), with its landmarks file beside it turned alike.
void showMoveRerunAndSave(const std::string& name, const glm::quat& turn) {
  const fs::path dir = testing_support::freshTempDir(name);
  auto avatar = eng::loadModel(testing_support::sharedDir() / "speech/rpm-visemes.glb");
  ASSERT_TRUE(avatar) << avatar.error().message;
  eng::turnAtRoots(*avatar, turn);
  ASSERT_TRUE(eng::saveModel(*avatar, dir / "rpm.glb"));
  auto original = autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/rpm-visemes.landmarks.json");
  ASSERT_TRUE(original) << original.error().message;
  for (glm::vec3& p : original->points) p = turn * p;
  ASSERT_TRUE(autorig::writeLandmarksFile(*original, dir / "rpm.landmarks.json"));
  testing_support::writeFile(dir / "landmarks.txt",
                             "0.2 landmarks-show\n"
                             "0.3 landmark-move 57 0 6     # the lower lip's middle, 6 px down\n"
                             "0.35 screenshot shown.png\n"
                             "0.4 landmark-move 8 0 4000   # far off the face: refused, the point stays\n"
                             "0.5 autorig-rerun\n"
                             "0.6 landmarks-save\n"
                             "0.7 quit\n");
  // The face is rigged on the fly into a cache of the test's own.
  setenv("XDG_CACHE_HOME", (dir / "cache").c_str(), 1);
  const editor_test::EditorRun run = editor_test::runEditor(dir, "--model rpm.glb --script landmarks.txt", 60.0f);
  unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(run.exitCode, 1) << "the refused move fails the run:\n" << run.log;
  EXPECT_NE(run.log.find("68 landmarks from rpm.landmarks.json"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("landmark 57 moved to"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("landmark 8 cannot move to pixel"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("transfer run again from the landmarks as they are"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("landmarks saved to rpm.landmarks.json"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("Validation"), std::string::npos) << run.log;

  // The points are drawn over the face: green dots in the middle of the viewport.
  auto shown = eng::readImage(dir / "shown.png");
  ASSERT_TRUE(shown) << shown.error().message;
  size_t green = 0;
  for (int y = 0; y < 560; ++y)
    for (int x = 320; x < 960; ++x) {
      const glm::ivec3 p = editor_test::pixel(*shown, x, y);
      if (p.g > p.r + 40 && p.g > p.b + 30) ++green;
    }
  EXPECT_GT(green, 68u * 4u) << "68 dots of a few pixels each";

  // Saved as the file holds the face; moved down the face, in its own frame.
  auto saved = autorig::readLandmarksFile(dir / "rpm.landmarks.json");
  ASSERT_TRUE(saved) << saved.error().message;
  const float eyeSpan = glm::distance(original->points[36], original->points[45]);
  const float lipMoved = glm::distance(saved->points[57], original->points[57]);
  EXPECT_GT(lipMoved, 0.01f * eyeSpan) << "6 px on a face about 200 px across";
  EXPECT_LT(lipMoved, 0.3f * eyeSpan);
  const glm::quat back = glm::inverse(turn);
  EXPECT_LT((back * saved->points[57]).y, (back * original->points[57]).y) << "down";
  EXPECT_EQ(saved->points[8], original->points[8]);
  EXPECT_EQ(saved->points[30], original->points[30]);
}

TEST(EditorLandmarks, ShowMoveRerunAndSave) {
  REQUIRE_XVFB();
  FACIAL_REQUIRE_SHARED();
  showMoveRerunAndSave("editor_landmarks", glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
}

// The avatar lying on its back in its file (a Z-up export): shown stood up,
// its points drawn on it, moved down its face and saved as the file holds it.
TEST(EditorLandmarks, AFaceItsFileHoldsLyingIsEditedStoodUp) {
  REQUIRE_XVFB();
  FACIAL_REQUIRE_SHARED();
  showMoveRerunAndSave("editor_landmarks_lying", glm::angleAxis(glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)));
}

TEST(EditorLandmarks, AMoveOutsideTheLandmarksIsRefusedNamingTheLine) {
  const fs::path dir = testing_support::freshTempDir("editor_landmarks_broken");
  const fs::path program = fs::path(FACIAL_BINARY_DIR) / "bin" / "facial-editor";
  for (const char* index : {"68", "-1", "2.5"}) {
    testing_support::writeFile(dir / "bad.txt", std::string("1 landmark-move ") + index + " 0 1\n");
    const std::string command = "cd '" + dir.string() + "' && DISPLAY= '" + program.string() + "' --script bad.txt >log.txt 2>&1";
    const int status = std::system(command.c_str());
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 1);
    EXPECT_NE(editor_test::readText(dir / "log.txt").find("bad.txt:1: landmark-move " + std::string(index) + " is not a landmark index (0-67)"),
              std::string::npos)
        << editor_test::readText(dir / "log.txt");
  }
}

}  // namespace
