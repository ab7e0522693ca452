#pragma once
// The window demo's hold on the single face, over its graph: the intensity
// slider poses one expression preset directly (lerp from the model's
// defaults); the 2D pad moves the cursor of a control map graph of its own
// (the study's ControlMapNode: four presets on the axes around neutral, and
// blinks on top so the face stays alive while it is held). Whichever was used
// last is eased in over about 0.25 s, and out again when the graph takes back
// control (a trigger, "back to the graph"), so taking and releasing control
// never pops. applyTo() hands the pose and its amount to the face's
// facial::Character (Character::overridePose).
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_setup.h"
#include "facial/character.h"

namespace cli {

// Who decides the weights of the (single) face.
enum class Control { Graph, Slider, Pad };

class FaceOverride {
 public:
  // `setup` must outlive the override. withPad: the pad's graph is built
  // (graphPath names it in errors); without it (a crowd) setPad does nothing.
  static eng::Result<FaceOverride> create(app::FaceSetup& setup, const std::filesystem::path& graphPath,
                                          uint64_t seed, bool withPad);

  // A trigger was pressed: the graph takes control; the slider poses this
  // emotion (index into kEmotions) from now on, unless it is neutral (0).
  void chooseEmotion(int emotion);
  // The slider: the chosen emotion's preset at `intensity` (clamped to [0, 1]) takes control.
  void setIntensity(float intensity);
  // The pad: its cursor (clamped to [-1, 1]^2) takes control.
  void setPad(glm::vec2 cursor);
  void returnToGraph() { control_ = Control::Graph; }

  // Eases towards whoever has control and runs the pad's graph while it shows.
  void update(float dt);
  // The face shows the pose by the current amount from its next update().
  void applyTo(facial::Character& face) const;

  Control control() const { return control_; }
  int chosen() const { return chosen_; }
  float intensity() const { return intensity_; }
  glm::vec2 pad() const { return pad_; }
  bool hasPad() const { return padGraph_.has_value(); }

 private:
  FaceOverride() = default;

  app::FaceSetup* setup_ = nullptr;  // not const: its expressionWeights() reuses scratch
  std::vector<float> weights_;      // the pose: one weight per target
  std::vector<float> expressions_;  // the same for a VRM rig's expressions (material binds)
  float amount_ = 0.0f;             // how much of the pose shows (0: the graph alone)
  Control control_ = Control::Graph;
  Control lastOverride_ = Control::Slider;  // what weights_ shows while easing out
  int chosen_ = 1;  // the slider's expression (happy until a trigger says otherwise)
  float intensity_ = 1.0f;
  glm::vec2 pad_{0.0f};
  std::optional<facial::Character> padGraph_;  // the pad's control map graph, over the same rig
};

}  // namespace cli
