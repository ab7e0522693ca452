#pragma once
// What the window demo's camera shows: an orbit camera framed on the faces
// (their heads, or with F the whole models; the orbit angles and the zoom the
// user chose are kept when the framing changes), turned by drags and zoomed
// by the wheel, and moved aside in the picture when the panel would cover the
// faces. No ImGui here: the window passes its size and the panel's extent in.
#include <array>

#include <glm/glm.hpp>

#include "engine/scene/model.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/scene_view.h"

namespace cli {

class DemoCamera {
 public:
  // bounds: the faces' box by eng::FramingMode (the heads, the whole models).
  DemoCamera(const std::array<eng::Aabb, 2>& bounds, eng::FramingMode framing, float aspect);

  const eng::OrbitCamera& camera() const { return view_.camera; }
  void orbit(float yawDegrees, float pitchDegrees);
  // One wheel step is 10 % closer (or further), within 0.3x to 8x.
  void zoom(float wheelSteps);
  // Frames the other part (heads / whole models) for a window of `display` pixels; says which.
  eng::FramingMode toggleFraming(glm::vec2 display);

  // Where the panel was drawn this frame (window pixels).
  void notePanel(float left, float right, float bottom);
  // The view to draw in a window of `display` pixels: the faces are framed in
  // the wider side the panel leaves free when the panel covers them (a small
  // panel in a corner does not move them), so a small window never hides half a face.
  eng::vk::SceneView shownView(glm::vec2 display) const;

 private:
  eng::vk::SceneView view_;
  std::array<eng::Aabb, 2> bounds_;
  eng::FramingMode framing_;
  eng::Aabb framed_;  // what view_ frames: bounds_[framing_]
  float panelLeft_ = 0.0f, panelRight_ = 0.0f, panelBottom_ = 0.0f;
};

}  // namespace cli
