#pragma once
// State machine panel: a graph file (graph_json.h) running on the face; its
// state machine's states with the current one and the transition progress,
// a button per trigger parameter and widgets for float / bool parameters.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/face_setup.h"
#include "editor/app/face_delegate.h"
#include "facial/runtime/character/face_driver.h"

namespace editor {

class StateMachinePanel {
 public:
  // Loads `graphPath`; the error names the file.
  eng::Result<void> load(const app::FaceSetup& face, const std::string& graphPath);
  void update(float dt);
  void draw(FaceDelegate& face);

  std::span<const float> targetWeights() const { return driver_->targetWeights(); }
  const facial::FaceDriver& driver() const { return *driver_; }
  // The current state's name ("" without a state machine).
  std::string currentState() const;
  // Fires a trigger parameter by name; false when the graph has none.
  bool fire(std::string_view trigger);
  bool hasTrigger(std::string_view trigger) const;
  // A trigger button: fires it and gives the face to the state machine.
  bool pressTrigger(std::string_view trigger, FaceDelegate& face);

 private:
  const app::FaceSetup* face_ = nullptr;
  std::optional<facial::FaceDriver> driver_;
  std::optional<facial::NodeIndex> machine_;
  std::string loadedPath_;
  char pathInput_[512] = {};
  PanelMessage message_;
};

}  // namespace editor
