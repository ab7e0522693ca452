// The landmarks file: what a user writes when detection fails. Bad files are
// refused with one line naming the file and the point.
#include "autorig/face_landmarks.h"

#include <gtest/gtest.h>

#include "tests/common/test_meshes.h"
#include "tests/common/test_support.h"

namespace {

// 68 points on the unit sphere's front, eye corners 36 and 45 apart.
autorig::FaceLandmarks pointsOnSphere() {
  autorig::FaceLandmarks l;
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const float a = -0.6f + 1.2f * float(i) / float(autorig::kLandmarkCount - 1);
    l.points[i] = glm::vec3(std::sin(a), 0.1f * std::cos(3.0f * a), std::cos(a));
    l.points[i] = glm::normalize(l.points[i]);
  }
  l.source = "test";
  return l;
}

std::string pointsJson(size_t count, const std::string& last = "[0, 0, 1]") {
  std::string text = "{\"landmarks68\": [";
  for (size_t i = 0; i + 1 < count; ++i) text += "[0, 0, 1], ";
  return text + last + "]}";
}

TEST(FaceLandmarksFile, WrittenAndReadBack) {
  const auto dir = testing_support::freshTempDir("face_landmarks_file");
  const autorig::FaceLandmarks written = pointsOnSphere();
  ASSERT_TRUE(autorig::writeLandmarksFile(written, dir / "l.json"));
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);
  auto read = autorig::readLandmarksFile(dir / "l.json");
  ASSERT_TRUE(read) << read.error().message;
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) EXPECT_NEAR(glm::distance(read->points[i], written.points[i]), 0.0f, 1e-6f);
  EXPECT_EQ(read->source, (dir / "l.json").string());
}

TEST(FaceLandmarksFile, BadFilesNameTheFileAndThePoint) {
  const auto dir = testing_support::freshTempDir("face_landmarks_bad");
  const struct {
    std::string name, text, expected;
  } cases[] = {
      {"67.json", pointsJson(67), "67.json: /landmarks68: 67 points, not the 68 of the iBUG layout"},
      {"nan.json", pointsJson(68, "[0, \"NaN\", 1]"), "nan.json: /landmarks68/67/1: landmark 67 is not three finite numbers"},
      {"two.json", pointsJson(68, "[0, 1]"), "two.json: /landmarks68/67: landmark 67 has 2 numbers, not 3 (x, y, z)"},
      {"none.json", "{\"points\": []}", "none.json: "},
      {"text.json", "not json", "text.json: "},
  };
  for (const auto& c : cases) {
    testing_support::writeFile(dir / c.name, c.text);
    auto read = autorig::readLandmarksFile(dir / c.name);
    ASSERT_FALSE(read) << c.name;
    EXPECT_NE(read.error().message.find((dir / c.expected).string()), std::string::npos) << read.error().message;
  }
}

TEST(FaceLandmarksFile, NotFiniteIsNotWritten) {
  const auto dir = testing_support::freshTempDir("face_landmarks_nan");
  autorig::FaceLandmarks l = pointsOnSphere();
  l.points[12].y = NAN;
  auto written = autorig::writeLandmarksFile(l, dir / "l.json");
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find("landmark 12 is not finite"), std::string::npos) << written.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir / "l.json"));
}

TEST(FaceLandmarksOnSurface, APointOffTheSurfaceIsNamed) {
  const eng::Model sphere = testing_support::makeSphereModel({.rings = 48, .segments = 64, .targets = 0});
  const autorig::PosedFace posed = autorig::poseAtRest(sphere);
  autorig::FaceLandmarks l = pointsOnSphere();
  EXPECT_TRUE(autorig::checkLandmarksOnSurface(l, sphere, posed, "l.json"));
  l.points[30] *= 1.3f;
  auto checked = autorig::checkLandmarksOnSurface(l, sphere, posed, "l.json");
  ASSERT_FALSE(checked);
  EXPECT_TRUE(checked.error().message.starts_with("l.json: landmark 30 is 0.3"))
      << checked.error().message;
  l.points[45] = l.points[36];
  checked = autorig::checkLandmarksOnSurface(l, sphere, posed, "l.json");
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().message, "l.json: landmarks 36 and 45 (the outer eye corners) coincide");
}

}  // namespace
