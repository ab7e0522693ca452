// The editor's landmark model (editor/landmark_edit_model.h) on facecap
// (../shared/assets/facecap.glb) with the landmarks dlib found on it: a point
// picked by its pixel, dragged over the skin (never off it), the transfer run
// again through app::FaceAutorig, the points saved and read back.
#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "app/face_autorig.h"
#include "autorig/face_frame.h"
#include "autorig/surface_cast.h"
#include "editor/landmark_edit_model.h"
#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

struct Facecap {
  eng::Model model;
  autorig::FaceLandmarks landmarks;
  autorig::PictureCamera camera;  // straight on, 512 px square
};

std::optional<Facecap> loadFacecap() {
  auto model = eng::loadModel(testing_support::sharedDir() / "assets/facecap.glb");
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return std::nullopt;
  }
  auto landmarks = autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/facecap.landmarks.json");
  if (!landmarks) {
    ADD_FAILURE() << landmarks.error().message;
    return std::nullopt;
  }
  const autorig::LandmarkFrame frame(*landmarks);
  const glm::vec3 centre = frame.origin();
  const glm::mat4 view = glm::lookAt(centre + frame.forward() * (4.0f * frame.eyeSpan()), centre, frame.up());
  const glm::mat4 projection = glm::perspective(glm::radians(30.0f), 1.0f, 0.1f * frame.eyeSpan(), 10.0f * frame.eyeSpan());
  return Facecap{std::move(*model), *landmarks, {projection * view, glm::vec2(512.0f)}};
}

TEST(LandmarkEditModel, PicksMovesOverTheSkinRerunsAndSaves) {
  FACIAL_REQUIRE_SHARED();
  const std::optional<Facecap> face = loadFacecap();
  ASSERT_TRUE(face);
  auto edit = editor::LandmarkEditModel::create(face->model, face->landmarks, "facecap.glb");
  ASSERT_TRUE(edit) << edit.error().message;
  EXPECT_FALSE(edit->dirty());
  EXPECT_FALSE(edit->moveSelected({4, 0}, face->camera)) << "nothing selected yet";
  EXPECT_FALSE(edit->select(68));

  // The chin (8), picked a few pixels off its projection.
  const glm::vec2 chin = *autorig::projectToPicture(face->camera, face->landmarks.points[8]);
  EXPECT_EQ(edit->pointAt(chin + glm::vec2(2, -1), 6.0f, face->camera), 8);
  EXPECT_EQ(edit->pointAt(chin + glm::vec2(40, 0), 6.0f, face->camera), -1);
  ASSERT_TRUE(edit->select(8));

  // Dragged 10 px: it lands 10 px over in the picture, on the skin.
  ASSERT_TRUE(edit->moveSelected({10, 0}, face->camera));
  const glm::vec2 moved = *autorig::projectToPicture(face->camera, edit->points()[8]);
  EXPECT_NEAR(moved.x, chin.x + 10.0f, 1.0f);
  EXPECT_NEAR(moved.y, chin.y, 1.0f);
  const autorig::PosedFace posed = autorig::poseAtRest(face->model);
  EXPECT_LT(autorig::distanceToSurface(face->model, posed, edit->points()[8]), 1e-3f * autorig::LandmarkFrame(face->landmarks).eyeSpan());
  EXPECT_TRUE(edit->dirty());
  EXPECT_TRUE(edit->unsaved());

  // Off the face: refused, the point stays.
  const glm::vec3 before = edit->points()[8];
  const eng::Result<void> off = edit->moveSelected({2000, 0}, face->camera);
  ASSERT_FALSE(off);
  EXPECT_NE(off.error().message.find("no skin of the face there"), std::string::npos) << off.error().message;
  EXPECT_EQ(edit->points()[8], before);

  // The transfer again, from the moved points.
  auto rigger = app::FaceAutorig::load();
  ASSERT_TRUE(rigger) << rigger.error().message;
  autorig::FaceLandmarks used;
  auto rigged = edit->rerun([&](const eng::Model& model, const autorig::FaceLandmarks& landmarks) -> eng::Result<eng::Model> {
    used = landmarks;
    auto made = rigger->rig(model, landmarks, "facecap.glb");
    if (!made) return made.error();
    return std::move(made->model);
  });
  ASSERT_TRUE(rigged) << rigged.error().message;
  EXPECT_EQ(used.points[8], before);
  EXPECT_FALSE(edit->dirty());
  size_t targets = 0;
  for (const eng::Mesh& mesh : rigged->meshes) targets += mesh.targetNames.size();
  EXPECT_GT(targets, 52u) << "facecap's own 52 and the units made";

  // Saved and read back: the moved point.
  const fs::path file = testing_support::freshTempDir("landmark_edit") / "facecap.landmarks.json";
  ASSERT_TRUE(edit->save(file));
  EXPECT_FALSE(edit->unsaved());
  auto read = autorig::readLandmarksFile(file);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_LT(glm::distance(read->points[8], before), 1e-5f);
  EXPECT_LT(glm::distance(read->points[30], face->landmarks.points[30]), 1e-5f);
}

TEST(LandmarkEditModel, LandmarksOffTheFaceAreRefusedNamingTheFile) {
  FACIAL_REQUIRE_SHARED();
  std::optional<Facecap> face = loadFacecap();
  ASSERT_TRUE(face);
  face->landmarks.points[30] += autorig::LandmarkFrame(face->landmarks).forward();  // an eye span out of the nose
  auto edit = editor::LandmarkEditModel::create(face->model, face->landmarks, "facecap.landmarks.json");
  ASSERT_FALSE(edit);
  EXPECT_NE(edit.error().message.find("facecap.landmarks.json: landmark 30 is"), std::string::npos) << edit.error().message;
}

}  // namespace
