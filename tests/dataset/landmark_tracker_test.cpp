// The 68 landmarks follow the expression: evaluated on the morphed built-in
// head, the brows rise in surprise and the chin drops with the jaw.
#include <gtest/gtest.h>

#include "app/face_setup.h"
#include "autorig/builtin_source.h"
#include "dataset/landmark_tracker.h"

namespace dataset {
namespace {

class LandmarkTrackerOnHead : public ::testing::Test {
 protected:
  void SetUp() override {
    auto face = app::FaceSetup::load({.program = "test"});
    ASSERT_TRUE(face) << face.error().message;
    face_ = std::make_unique<app::FaceSetup>(std::move(*face));
    auto source = autorig::builtInSource(face_->model());
    ASSERT_TRUE(source) << source.error().message;
    rest_ = source->landmarks;
    auto tracker = LandmarkTracker::bind(face_->model(), rest_);
    ASSERT_TRUE(tracker) << tracker.error().message;
    tracker_.emplace(std::move(*tracker));
  }
  Landmarks3 posed(const std::string& expression, float intensity) {
    std::vector<float> weights(face_->weightCount());
    auto preset = face_->findExpression(expression);
    EXPECT_TRUE(preset);
    EXPECT_TRUE(face_->expressionWeights(**preset, intensity, weights));
    Landmarks3 points{};
    EXPECT_TRUE(tracker_->evaluate(weights, points));
    return points;
  }
  std::unique_ptr<app::FaceSetup> face_;
  autorig::FaceLandmarks rest_;
  std::optional<LandmarkTracker> tracker_;
};

TEST_F(LandmarkTrackerOnHead, AtRestTheyAreTheHeadsOwnLandmarks) {
  const Landmarks3 neutral = posed("neutral", 1.0f);
  for (size_t i = 0; i < neutral.size(); ++i) EXPECT_LT(glm::length(neutral[i] - rest_.points[i]), 2e-4f) << "landmark " << i;
}

TEST_F(LandmarkTrackerOnHead, BrowsRiseAndTheChinDropsInSurprise) {
  const Landmarks3 neutral = posed("neutral", 1.0f);
  const Landmarks3 surprise = posed("surprise", 1.0f);
  for (size_t brow : {19u, 24u}) EXPECT_GT(surprise[brow].y - neutral[brow].y, 0.003f) << "brow landmark " << brow;
  EXPECT_LT(surprise[8].y - neutral[8].y, -0.004f) << "chin";
  EXPECT_LT(surprise[57].y - neutral[57].y, -0.004f) << "lower lip";
  // The nose bridge does not move with the expression.
  EXPECT_LT(glm::length(surprise[27] - neutral[27]), 1e-3f);
}

TEST_F(LandmarkTrackerOnHead, WrongWeightCountIsRefused) {
  std::vector<float> weights(3);
  Landmarks3 points{};
  auto result = tracker_->evaluate(weights, points);
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("3 weights"), std::string::npos);
}

TEST(ProjectLandmarks, TheOrbitTargetLandsInTheImageCentre) {
  eng::OrbitCamera camera;
  camera.target = {0.1f, 0.2f, 0.0f};
  camera.yawDegrees = 20.0f;
  Landmarks3 points{};
  points.fill(camera.target);
  const Landmarks2 pixels = projectLandmarks(points, camera, 200, 100);
  EXPECT_NEAR(pixels[0].x, 100.0f, 1e-3f);
  EXPECT_NEAR(pixels[0].y, 50.0f, 1e-3f);
  // Above the target is up in the picture (y down).
  points[1] = camera.target + glm::vec3(0.0f, 0.1f, 0.0f);
  EXPECT_LT(projectLandmarks(points, camera, 200, 100)[1].y, 50.0f);
}

}  // namespace
}  // namespace dataset
