#include "cli/demo/demo_camera.h"

#include <algorithm>
#include <cmath>

namespace cli {

DemoCamera::DemoCamera(const std::array<eng::Aabb, 2>& bounds, eng::FramingMode framing, float aspect)
    : bounds_(bounds), framing_(framing), framed_(bounds[size_t(framing)]) {
  view_.camera = eng::OrbitCamera::frame(framed_, aspect);
}

void DemoCamera::orbit(float yawDegrees, float pitchDegrees) {
  view_.camera.yawDegrees += yawDegrees;
  view_.camera.pitchDegrees = std::clamp(view_.camera.pitchDegrees + pitchDegrees, -80.0f, 80.0f);
}

void DemoCamera::zoom(float wheelSteps) {
  view_.camera.zoom = std::clamp(view_.camera.zoom * std::pow(1.1f, wheelSteps), 0.3f, 8.0f);
}

eng::FramingMode DemoCamera::toggleFraming(glm::vec2 display) {
  framing_ = framing_ == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face;
  framed_ = bounds_[size_t(framing_)];
  const float aspect = display.x > 0.0f && display.y > 0.0f ? display.x / display.y : 1.0f;
  const eng::OrbitCamera framed = eng::OrbitCamera::frame(framed_, aspect, view_.camera.fovYDegrees);
  view_.camera.target = framed.target;
  view_.camera.distance = framed.distance;
  view_.camera.sceneRadius = framed.sceneRadius;
  return framing_;
}

void DemoCamera::notePanel(float left, float right, float bottom) {
  panelLeft_ = left;
  panelRight_ = right;
  panelBottom_ = bottom;
}

eng::vk::SceneView DemoCamera::shownView(glm::vec2 display) const {
  eng::vk::SceneView shown = view_;
  if (!(display.x > 0.0f) || !(display.y > 0.0f)) return shown;
  // Where the framed faces land in the whole window (their box's corners).
  const glm::mat4 viewProj = shown.camera.projection(display.x / display.y) * shown.camera.view();
  glm::vec2 lo = display, hi(0.0f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? framed_.max.x : framed_.min.x, corner & 2 ? framed_.max.y : framed_.min.y,
                      corner & 4 ? framed_.max.z : framed_.min.z};
    const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return shown;
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * display;
    lo = glm::min(lo, pixel);
    hi = glm::max(hi, pixel);
  }
  const bool covered = panelRight_ > lo.x && panelLeft_ < hi.x && panelBottom_ > lo.y;
  if (!covered) return shown;
  constexpr float kGap = 8.0f;
  const float rightFree = display.x - panelRight_ - kGap, leftFree = panelLeft_ - kGap;
  if (rightFree >= leftFree)
    shown.camera.fitToRegion(framed_, display, {panelRight_ + kGap, 0.0f}, display);
  else
    shown.camera.fitToRegion(framed_, display, {0.0f, 0.0f}, {leftFree, display.y});
  return shown;
}

}  // namespace cli
