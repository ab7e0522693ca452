#pragma once
// State machine panel: a graph file (graph_json.h) running on the face; its
// state machine's states with the current one and the transition progress,
// a button per trigger parameter and widgets for float / bool parameters.
// Its Speak box (app/speech_box.h) makes the face say a typed line aloud
// under the graph's emotion: audio::LiveSpeech plays it and the graph's face
// driver follows the audio clock; speaking gives the face to the graph.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/face_setup.h"
#include "app/speech_box.h"
#include "audio/live_speech.h"
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

  // The Speak box, for the script: its fields, Speak (false, the problem
  // shown and logged, when the line cannot be spoken) and Stop.
  void setSpeechText(std::string_view text) { speechBox_.setText(text); }
  void setSpeechLanguage(std::string_view language) { speechBox_.setLanguage(language); }
  bool pressSpeak(FaceDelegate& face);
  void pressStopSpeaking();
  // Before the first line: the voice is not played (tests; the mouth still moves).
  void muteSpeech() { speech_ = audio::LiveSpeech({.silent = true}); }

 private:
  const app::FaceSetup* face_ = nullptr;
  std::optional<facial::FaceDriver> driver_;
  std::optional<facial::NodeIndex> machine_;
  std::string loadedPath_;
  char pathInput_[512] = {};
  PanelMessage message_;
  audio::LiveSpeech speech_;
  app::SpeechBox speechBox_;
  float speechTime_ = 0.0f;
  bool speechShown_ = false;  // the face speaks a line that has not yet been logged as done
};

}  // namespace editor
