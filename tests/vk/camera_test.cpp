// Orbit camera framing and conventions.
#include "engine/vk/camera.h"

#include <gtest/gtest.h>

namespace {

glm::vec3 project(const eng::vk::OrbitCamera& c, float aspect, glm::vec3 p) {
  const glm::vec4 clip = c.projection(aspect) * c.view() * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}

TEST(OrbitCamera, DefaultLooksAtTheFaceFromPlusZ) {
  const eng::Aabb box{{-1.0f, -2.0f, -0.5f}, {1.0f, 2.0f, 0.5f}};
  const eng::vk::OrbitCamera c = eng::vk::OrbitCamera::frame(box);
  EXPECT_EQ(c.target, box.center());
  const glm::vec3 eye = c.position();
  EXPECT_NEAR(eye.x, 0.0f, 1e-5f);
  EXPECT_NEAR(eye.y, 0.0f, 1e-5f);
  EXPECT_GT(eye.z, 0.5f);
}

TEST(OrbitCamera, FramedBoxFitsTheImageAndFillsMostOfIt) {
  const eng::Aabb box{{-1.0f, -2.0f, -0.5f}, {1.0f, 2.0f, 0.5f}};
  for (float aspect : {1.0f, 0.5f, 2.0f}) {
    const eng::vk::OrbitCamera c = eng::vk::OrbitCamera::frame(box, aspect);
    float maxY = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p{corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                        corner & 4 ? box.max.z : box.min.z};
      const glm::vec3 ndc = project(c, aspect, p);
      EXPECT_LE(std::abs(ndc.x), 1.0f) << "aspect " << aspect;
      EXPECT_LE(std::abs(ndc.y), 1.0f) << "aspect " << aspect;
      EXPECT_GE(ndc.z, 0.0f);
      EXPECT_LE(ndc.z, 1.0f);
      maxY = std::max(maxY, std::abs(ndc.y));
    }
    if (aspect >= 1.0f) EXPECT_GT(maxY, 0.75f) << "tall box fills the height";
  }
}

TEST(OrbitCamera, VulkanClipSpaceHasYDown) {
  const eng::vk::OrbitCamera c = eng::vk::OrbitCamera::frame({{-1, -1, -1}, {1, 1, 1}});
  EXPECT_LT(project(c, 1.0f, {0.0f, 0.9f, 0.0f}).y, 0.0f) << "world up is image up (negative clip y)";
  EXPECT_LT(project(c, 1.0f, {-0.9f, 0.0f, 0.0f}).x, 0.0f) << "world -X on the left seen from +Z";
}

TEST(OrbitCamera, YawPitchAndZoomOrbitTheTarget) {
  eng::vk::OrbitCamera c = eng::vk::OrbitCamera::frame({{-1, -1, -1}, {1, 1, 1}});
  const float d = glm::length(c.position() - c.target);
  c.yawDegrees = 90.0f;
  EXPECT_NEAR(c.position().x, d, 1e-4f);
  c.yawDegrees = 0.0f;
  c.pitchDegrees = 30.0f;
  EXPECT_GT(c.position().y, 0.0f);
  c.pitchDegrees = 0.0f;
  c.zoom = 2.0f;
  EXPECT_NEAR(glm::length(c.position() - c.target), d / 2.0f, 1e-4f);
}

}  // namespace
