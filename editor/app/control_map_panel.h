#pragma once
// Control map panel: a 2D pad over the study's four-pole control map
// (controlMap node: happy +x, sad -x, surprise +y, anger -y) or a six-pole
// freeform map (freeformMap node, the basic emotions around a circle).
// Dragging the cursor sets the graph's x / y parameters; the graph poses the face.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_setup.h"
#include "editor/app/face_delegate.h"
#include "facial/runtime/character/face_driver.h"

namespace editor {

class ControlMapPanel {
 public:
  enum class Layout { FourPoles, SixPoles };
  struct Pole {
    const char* emotion;
    glm::vec2 at;
  };

  eng::Result<void> create(const app::FaceSetup& face);
  void update(float dt);
  void draw(FaceDelegate& face);

  // Moves the cursor (clamped by the map) and takes control of the face.
  void setCursor(glm::vec2 cursor);
  // The pad dragged to `cursor`: moves it and gives the face to the control map.
  void dragCursor(glm::vec2 cursor, FaceDelegate& face);
  glm::vec2 cursor() const { return cursor_; }
  void setLayout(Layout layout) { layout_ = layout; }
  std::span<const float> targetWeights() const { return active().targetWeights(); }
  const facial::FaceDriver& active() const { return *drivers_[size_t(layout_)]; }

 private:
  std::array<std::optional<facial::FaceDriver>, 2> drivers_;
  std::array<facial::ParameterIndex, 2> x_{}, y_{};
  Layout layout_ = Layout::FourPoles;
  glm::vec2 cursor_{0.0f};
  PanelMessage message_;
};

}  // namespace editor
