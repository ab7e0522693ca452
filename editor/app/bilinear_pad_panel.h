#pragma once
// Bilinear pad panel: the study's bilinear interpolation (editor/bilinear_pad.h)
// as a 2D pad, t across (the "from" column -> the "to" column), s up (row 1
// -> row 2), over four keyframe poses picked from the face's expression
// presets. Picking a new "to" expression mid-way re-bases as the study does
// (the face does not jump; the cursor returns to t = 0). Dragging the cursor
// gives the face to the pad.
#include <array>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_setup.h"
#include "editor/app/face_delegate.h"
#include "editor/bilinear_pad.h"

namespace editor {

class BilinearPadPanel {
 public:
  eng::Result<void> create(const app::FaceSetup& face);
  void update();
  void draw(FaceDelegate& face);

  // The pad dragged to (s, t) in [0, 1]^2: gives the face to the pad.
  void dragTo(float s, float t, FaceDelegate& face);
  // A corner's expression combo; false (reported) for an unknown preset.
  bool chooseCorner(BilinearPad::Corner corner, std::string_view preset);
  const BilinearPad& pad() const { return pad_; }
  std::span<const float> targetWeights() const { return targets_; }
  std::span<const float> expressionWeights() const { return expressionWeights_; }
  // A rig input (action unit or emotion) on the pad's face; 0 for other names.
  float channelValue(std::string_view channel) const;

 private:
  eng::Result<std::vector<float>> presetPose(std::string_view preset) const;

  const app::FaceSetup* face_ = nullptr;
  BilinearPad pad_;
  std::array<std::string, 4> cornerNames_ = {"neutral", "happy", "sad", "surprise"};
  std::vector<float> inputs_;  // rig inputs: action units, then emotions
  std::vector<float> targets_, expressionWeights_;
  PanelMessage message_;
};

}  // namespace editor
