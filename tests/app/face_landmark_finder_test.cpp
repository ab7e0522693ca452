// Landmarks found on real faces land where a face's features are; faces with
// no front, and no face at all, are refused with one line naming the file.
#include "app/face_landmark_finder.h"
#include "autorig/face_parts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/gltf_loader.h"
#include "tests/common/test_meshes.h"
#include "tests/common/test_support.h"

namespace {

struct Found {
  eng::Model model;
  autorig::PosedFace posed;
  autorig::FaceLandmarks landmarks;
  autorig::FaceParts parts;
};

// The picture with the points drawn goes to build/test-tmp for a person to look at.
Found find(const std::filesystem::path& path, const std::string& pictureName) {
  Found f;
  auto model = eng::loadModel(path);
  EXPECT_TRUE(model) << model.error().message;
  if (!model) return f;
  f.model = std::move(*model);
  f.posed = autorig::poseAtRest(f.model);
  const auto picture = testing_support::freshTempDir("face_landmark_finder") / (pictureName + ".png");
  auto landmarks = app::findFaceLandmarks(f.model, f.posed, {.picture = picture});
  EXPECT_TRUE(landmarks) << landmarks.error().message;
  if (!landmarks) return f;
  f.landmarks = *landmarks;
  f.parts = autorig::findFaceParts(f.model, f.posed, f.landmarks);
  for (const std::string& note : f.parts.notes) std::printf("  %s\n", note.c_str());
  return f;
}

// The centre of the vertices of the posed mesh called `name`.
glm::vec3 meshCentre(const Found& f, const std::string& name) {
  glm::vec3 sum(0.0f);
  size_t n = 0;
  for (const autorig::PosedPrimitive& p : f.posed.primitives)
    if (f.model.meshes[p.mesh].name == name)
      for (const glm::vec3& v : p.positions) sum += v, ++n;
  return n ? sum / float(n) : glm::vec3(NAN);
}

// What every face's landmarks share, in units of the outer eye corners'
// distance: the layout's order left to right and top to bottom, the nose tip
// in front, the chin lowest.
void expectFaceLayout(const autorig::FaceLandmarks& l) {
  const auto& p = l.points;
  const float span = glm::distance(p[36], p[45]);
  ASSERT_GT(span, 0.0f);
  EXPECT_LT(p[36].x, p[39].x);
  EXPECT_LT(p[39].x, p[42].x);
  EXPECT_LT(p[42].x, p[45].x);
  EXPECT_LT(p[48].x, p[54].x);
  const float eyeY = (p[36].y + p[45].y) / 2.0f, mouthY = (p[48].y + p[54].y) / 2.0f;
  EXPECT_GT(eyeY, p[30].y);
  EXPECT_GT(p[30].y, mouthY);
  EXPECT_GT(mouthY, p[8].y);
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) EXPECT_GE(p[i].y, p[8].y - 0.02f * span) << "landmark " << i;
  // The nose tip stands out in front of the eyes' corners and the mouth's.
  EXPECT_GT(p[30].z, std::max({p[36].z, p[45].z, p[48].z, p[54].z}) + 0.1f * span);
  // Mouth and eye width, as faces have them (0.5-0.75 and 0.2-0.35 of the span).
  EXPECT_NEAR(glm::distance(p[48], p[54]) / span, 0.6f, 0.2f);
  EXPECT_NEAR(glm::distance(p[36], p[39]) / span, 0.28f, 0.1f);
}

// The share of the posed primitives of mesh `name` (all of them, or only
// primitive `primitive`) that is `part`.
float shareOf(const Found& f, const std::string& name, autorig::FacePart part, int primitive = -1) {
  size_t all = 0, of = 0;
  for (size_t i = 0; i < f.posed.primitives.size(); ++i) {
    const autorig::PosedPrimitive& p = f.posed.primitives[i];
    if (f.model.meshes[p.mesh].name != name || (primitive >= 0 && p.primitive != size_t(primitive))) continue;
    for (autorig::FacePart v : f.parts.vertexParts[i]) all += 1, of += v == part;
  }
  return all ? float(of) / float(all) : -1.0f;
}

TEST(FaceLandmarkFinder, BuiltInHeadFeaturesWhereTheMeshHasThem) {
  Found f = find(testing_support::sourceDir() / "data" / "head.glb", "head");
  ASSERT_TRUE(f.landmarks.source.starts_with("dlib")) << f.landmarks.source;
  expectFaceLayout(f.landmarks);
  const auto& p = f.landmarks.points;
  const float span = glm::distance(p[36], p[45]);
  // The head is symmetric about x = 0, the eyes sit over the eyeball meshes
  // (EyeRight is the subject's right: landmarks 36-41).
  EXPECT_NEAR(p[8].x, 0.0f, 0.05f * span);
  EXPECT_NEAR(p[30].x, 0.0f, 0.05f * span);
  EXPECT_NEAR(p[48].x + p[54].x, 0.0f, 0.08f * span);
  const glm::vec3 right = meshCentre(f, "EyeRight"), left = meshCentre(f, "EyeLeft");
  EXPECT_LT(glm::distance(glm::vec2((p[36] + p[39]) / 2.0f), glm::vec2(right)), 0.1f * span);
  EXPECT_LT(glm::distance(glm::vec2((p[42] + p[45]) / 2.0f), glm::vec2(left)), 0.1f * span);

  using autorig::FacePart;
  EXPECT_EQ(shareOf(f, "EyeRight", FacePart::EyeballRight), 1.0f);
  EXPECT_EQ(shareOf(f, "EyeLeft", FacePart::EyeballLeft), 1.0f);
  EXPECT_EQ(shareOf(f, "Head", FacePart::Skin, 0), 1.0f);
  EXPECT_EQ(shareOf(f, "Head", FacePart::Skin, 1), 1.0f);  // the mouth's inside moves with the skin
  EXPECT_EQ(shareOf(f, "Head", FacePart::UpperTeeth, 2), 1.0f);
  EXPECT_EQ(shareOf(f, "Head", FacePart::LowerTeeth, 3), 1.0f);
  EXPECT_EQ(shareOf(f, "Head", FacePart::Tongue, 4), 1.0f);
  EXPECT_EQ(shareOf(f, "Ears", FacePart::Skin), 1.0f);
  EXPECT_TRUE(f.parts.eyeballsFound);
  EXPECT_LT(glm::distance(f.parts.eyeCentres[0], right), 0.02f * span);
}

TEST(FaceLandmarkFinder, FacecapFeaturesWhereTheMeshHasThem) {
  const auto path = testing_support::sharedDir() / "assets" / "facecap.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "needs ../shared/assets/facecap.glb";
  Found f = find(path, "facecap");
  expectFaceLayout(f.landmarks);
  // Nothing is named: the eyeballs (meshes 0 and 1) and the teeth (mesh 3)
  // are told by their shapes and places.
  using autorig::FacePart;
  ASSERT_EQ(f.parts.vertexParts.size(), 4u);
  const auto all = [&](size_t i, FacePart part) {
    return std::all_of(f.parts.vertexParts[i].begin(), f.parts.vertexParts[i].end(), [&](FacePart v) { return v == part; });
  };
  EXPECT_TRUE((all(0, FacePart::EyeballLeft) && all(1, FacePart::EyeballRight)) ||
              (all(0, FacePart::EyeballRight) && all(1, FacePart::EyeballLeft)));
  EXPECT_TRUE(all(2, FacePart::Skin));
  const auto& teeth = f.parts.vertexParts[3];
  EXPECT_GT(std::count(teeth.begin(), teeth.end(), FacePart::UpperTeeth), 100);
  EXPECT_GT(std::count(teeth.begin(), teeth.end(), FacePart::LowerTeeth), 100);
  EXPECT_TRUE(f.parts.eyeballsFound);
}

TEST(FaceLandmarkFinder, ReadyPlayerMeAvatarFeaturesInOrder) {
  const auto path = testing_support::sharedDir() / "speech" / "rpm-visemes.glb";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "needs ../shared/speech/rpm-visemes.glb";
  Found f = find(path, "rpm-visemes");
  expectFaceLayout(f.landmarks);
  using autorig::FacePart;
  EXPECT_EQ(shareOf(f, "Wolf3D_Head", FacePart::Skin), 1.0f);
  EXPECT_EQ(shareOf(f, "EyeLeft", FacePart::EyeballLeft), 1.0f);  // ARKit's and RPM's Left: the subject's
  EXPECT_EQ(shareOf(f, "EyeRight", FacePart::EyeballRight), 1.0f);
  EXPECT_GT(shareOf(f, "Wolf3D_Teeth", FacePart::UpperTeeth), 0.3f);
  EXPECT_GT(shareOf(f, "Wolf3D_Teeth", FacePart::LowerTeeth), 0.3f);
  EXPECT_EQ(shareOf(f, "Wolf3D_Hair", FacePart::Hair), 1.0f);
  EXPECT_EQ(shareOf(f, "Wolf3D_Glasses", FacePart::Glasses), 1.0f);
  for (const char* clothes : {"Wolf3D_Body", "Wolf3D_Outfit_Top", "Wolf3D_Outfit_Bottom", "Wolf3D_Outfit_Footwear"})
    EXPECT_EQ(shareOf(f, clothes, FacePart::Other), 1.0f) << clothes;
  EXPECT_TRUE(f.parts.eyeballsFound);
}

TEST(FaceLandmarkFinder, SphereHasNoFace) {
  eng::Model sphere = testing_support::makeSphereModel(testing_support::whiteSphereSpec(2));
  sphere.sourcePath = "ball.glb";
  const autorig::PosedFace posed = autorig::poseAtRest(sphere);
  auto landmarks = app::findFaceLandmarks(sphere, posed);
  ASSERT_FALSE(landmarks);
  EXPECT_EQ(landmarks.error().message, "no face found in a front view of ball.glb");
}

// The built-in head turned round: the camera sees the back of its head.
TEST(FaceLandmarkFinder, HeadSeenFromTheBackHasNoFace) {
  auto model = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(model) << model.error().message;
  const glm::quat halfTurn = glm::angleAxis(glm::pi<float>(), glm::vec3(0.0f, 1.0f, 0.0f));
  for (eng::Node& node : model->nodes)
    if (node.parent < 0) node.rotation = halfTurn * node.rotation, node.translation = halfTurn * node.translation;
  const autorig::PosedFace posed = autorig::poseAtRest(*model);
  auto landmarks = app::findFaceLandmarks(*model, posed);
  ASSERT_FALSE(landmarks);
  EXPECT_NE(landmarks.error().message.find("no face found in a front view of"), std::string::npos)
      << landmarks.error().message;
}

TEST(FaceLandmarkFinder, MissingPredictorNamesTheFile) {
  eng::Model sphere = testing_support::makeSphereModel(testing_support::whiteSphereSpec(0));
  const autorig::PosedFace posed = autorig::poseAtRest(sphere);
  auto landmarks = app::findFaceLandmarks(sphere, posed, {.predictor = "/nonexistent/predictor.dat"});
  ASSERT_FALSE(landmarks);
  EXPECT_NE(landmarks.error().message.find("/nonexistent/predictor.dat: no such file"), std::string::npos)
      << landmarks.error().message;
}

}  // namespace
