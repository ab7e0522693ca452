// Orbit camera framing and conventions.
#include "engine/view/camera.h"

#include <gtest/gtest.h>

namespace {

glm::vec3 project(const eng::OrbitCamera& c, float aspect, glm::vec3 p) {
  const glm::vec4 clip = c.projection(aspect) * c.view() * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}

TEST(OrbitCamera, DefaultLooksAtTheFaceFromPlusZ) {
  const eng::Aabb box{{-1.0f, -2.0f, -0.5f}, {1.0f, 2.0f, 0.5f}};
  const eng::OrbitCamera c = eng::OrbitCamera::frame(box);
  EXPECT_EQ(c.target, box.center());
  const glm::vec3 eye = c.position();
  EXPECT_NEAR(eye.x, 0.0f, 1e-5f);
  EXPECT_NEAR(eye.y, 0.0f, 1e-5f);
  EXPECT_GT(eye.z, 0.5f);
}

TEST(OrbitCamera, FramedBoxFitsTheImageAndFillsMostOfIt) {
  const eng::Aabb box{{-1.0f, -2.0f, -0.5f}, {1.0f, 2.0f, 0.5f}};
  for (float aspect : {1.0f, 0.5f, 2.0f}) {
    const eng::OrbitCamera c = eng::OrbitCamera::frame(box, aspect);
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
    if (aspect >= 1.0f) {
      EXPECT_GT(maxY, 0.75f) << "tall box fills the height";
    }
  }
}

TEST(OrbitCamera, VulkanClipSpaceHasYDown) {
  const eng::OrbitCamera c = eng::OrbitCamera::frame({{-1, -1, -1}, {1, 1, 1}});
  EXPECT_LT(project(c, 1.0f, {0.0f, 0.9f, 0.0f}).y, 0.0f) << "world up is image up (negative clip y)";
  EXPECT_LT(project(c, 1.0f, {-0.9f, 0.0f, 0.0f}).x, 0.0f) << "world -X on the left seen from +Z";
}

TEST(OrbitCamera, YawPitchAndZoomOrbitTheTarget) {
  eng::OrbitCamera c = eng::OrbitCamera::frame({{-1, -1, -1}, {1, 1, 1}});
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

namespace {

TEST(OrbitCamera, ImageCentreMovesTheTargetThereAndKeepsTheShape) {
  const eng::Aabb box{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}};
  eng::OrbitCamera c = eng::OrbitCamera::frame(box, 1.5f);
  const glm::vec3 corner{1.0f, 1.0f, 1.0f};
  const glm::vec3 centredCorner = project(c, 1.5f, corner);
  c.imageCentre = {0.4f, -0.25f};
  const glm::vec3 target = project(c, 1.5f, c.target);
  EXPECT_NEAR(target.x, 0.4f, 1e-5f);
  EXPECT_NEAR(target.y, -0.25f, 1e-5f);
  const glm::vec3 shiftedCorner = project(c, 1.5f, corner);
  EXPECT_NEAR(shiftedCorner.x - centredCorner.x, 0.4f, 1e-5f);  // a pure translation in the image
  EXPECT_NEAR(shiftedCorner.y - centredCorner.y, -0.25f, 1e-5f);
  EXPECT_NEAR(shiftedCorner.z, centredCorner.z, 1e-6f);          // depth untouched
}

TEST(OrbitCamera, FitToRegionPutsTheFramingInTheFreePartOfTheWindow) {
  const eng::Aabb box{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}};
  const float aspect = 960.0f / 600.0f;
  const eng::OrbitCamera whole = eng::OrbitCamera::frame(box, aspect);
  eng::OrbitCamera region = whole;
  // A 440-pixel panel on the left: the face belongs in x 440..960.
  region.fitToRegion(box, {960.0f, 600.0f}, {440.0f, 0.0f}, {960.0f, 600.0f});
  const glm::vec3 target = project(region, aspect, region.target);
  EXPECT_NEAR((target.x + 1.0f) * 0.5f * 960.0f, 700.0f, 1e-2f);  // the region's centre column
  EXPECT_NEAR(target.y, 0.0f, 1e-5f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f};
    const float x = (project(region, aspect, p).x + 1.0f) * 0.5f * 960.0f;
    EXPECT_GE(x, 440.0f) << "corner " << corner << " is under the panel";
    EXPECT_LE(x, 960.0f) << "corner " << corner;
  }
  EXPECT_LT(region.zoom, whole.zoom);  // the free part is narrower than the cube needs

  // A tall, narrow box (a head) already fits beside the panel: moved, not shrunk.
  const eng::Aabb head{{-0.3f, -1.0f, -0.3f}, {0.3f, 1.0f, 0.3f}};
  eng::OrbitCamera beside = eng::OrbitCamera::frame(head, aspect);
  beside.fitToRegion(head, {960.0f, 600.0f}, {440.0f, 0.0f}, {960.0f, 600.0f});
  EXPECT_FLOAT_EQ(beside.zoom, 1.0f);
  region.fitToRegion(box, {0.0f, 600.0f}, {0.0f, 0.0f}, {1.0f, 1.0f});  // degenerate image: no change
  EXPECT_NEAR((project(region, aspect, region.target).x + 1.0f) * 0.5f * 960.0f, 700.0f, 1e-2f);
}

TEST(OrbitCamera, ViewRegionAsImageShowsTheRegionAsAPictureOfItsSizeShowsIt) {
  // An editor's free middle (640x541 below a menu bar in 1280x800) and
  // `facial play --size 640x541` of the same face, zoom and orbit.
  const eng::Aabb head{{-0.08f, -0.16f, -0.11f}, {0.08f, 0.13f, 0.11f}};
  const glm::vec2 window{1280.0f, 800.0f}, lo{320.0f, 19.0f}, hi{960.0f, 560.0f};
  const glm::vec2 region = hi - lo;
  eng::OrbitCamera picture = eng::OrbitCamera::frame(head, region.x / region.y);
  picture.zoom = 1.15f;
  picture.yawDegrees = 12.0f;
  picture.pitchDegrees = -4.0f;
  eng::OrbitCamera shown = picture;
  shown.distance = 7.0f;  // whatever the window had: the region decides
  shown.viewRegionAsImage(head, window, lo, hi);
  EXPECT_NEAR(glm::length(shown.position() - picture.position()), 0.0f, 1e-5f) << "the same viewpoint, so the same perspective";
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? head.max.x : head.min.x, corner & 2 ? head.max.y : head.min.y,
                      corner & 4 ? head.max.z : head.min.z};
    const glm::vec3 inPicture = project(picture, region.x / region.y, p);
    const glm::vec3 inWindow = project(shown, window.x / window.y, p);
    const glm::vec2 picturePixel = (glm::vec2(inPicture) * 0.5f + 0.5f) * region;
    const glm::vec2 windowPixel = (glm::vec2(inWindow) * 0.5f + 0.5f) * window - lo;
    EXPECT_NEAR(windowPixel.x, picturePixel.x, 1e-2f) << "corner " << corner;
    EXPECT_NEAR(windowPixel.y, picturePixel.y, 1e-2f) << "corner " << corner;
    EXPECT_NEAR(inWindow.z, inPicture.z, 1e-5f) << "corner " << corner;
  }
}

}  // namespace
