#pragma once
// State machine panel: a graph file (graph_json.h) running on the face; its
// state machine's states with the current one and the transition progress,
// a button per trigger parameter and widgets for float / bool parameters.
// Its Speak box (app/speech_box.h) makes the face say a typed line aloud
// under the graph's emotion: audio::LiveSpeech plays it and the graph's face
// driver follows the audio clock; speaking gives the face to the graph.
// Its diagram window (state_machine_panel_diagram.cpp) draws the state
// machine as boxes and arrows with the active state and the transition in
// flight, and edits it through a GraphDocument: every edit rebuilds the
// running graph (one the runtime refuses is undone and the reason shown), and
// Save writes the graph file the runtime reads.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/face_setup.h"
#include "app/speech_box.h"
#include "audio/live_speech.h"
#include "editor/app/face_delegate.h"
#include "editor/graph_document.h"
#include "editor/state_machine_diagram.h"
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

  // The diagram window, over the free part of the window at `at` (pixels).
  void drawDiagramWindow(glm::vec2 at, glm::vec2 size);
  void showDiagram() { diagramShown_ = true; }
  // The graph being edited (empty when the graph has no state machine).
  const std::optional<GraphDocument>& document() const { return document_; }
  // The diagram's edits (the script runs these too). Each returns false after
  // reporting why in the panel and the log; a success rebuilds the running graph.
  bool addState(std::string_view name, std::string_view expression);
  bool removeState(std::string_view name);
  bool renameState(std::string_view from, std::string_view to);
  bool addTransition(std::string_view from, std::string_view to, std::string_view trigger, float duration,
                     std::string_view easing);
  bool editTransition(std::string_view from, std::string_view to, float duration, std::string_view easing,
                      std::optional<float> exitTime, bool interruptible);
  bool removeTransition(std::string_view from, std::string_view to);
  bool undoGraphEdit();
  bool redoGraphEdit();
  bool saveGraph(const std::string& path);

 private:
  eng::Result<void> adopt(facial::SharedGraphDefinition graph, const std::string& graphPath);
  // Rebuilds the running graph from the document after an edit (`edited`);
  // an edit that fails, or that the runtime refuses, is reported and undone.
  bool applyEdit(const eng::Result<void>& edited, const std::string& what);
  bool rebuildFromDocument();
  void drawParameters();
  void drawDiagramCanvas();
  void tooltipForDiagram(glm::vec2 origin) const;
  void drawStateEditor();
  void drawTransitionEditor();
  void drawAddControls();
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
  std::optional<GraphDocument> document_;
  StateMachineDiagram diagram_;
  bool diagramShown_ = false;
  int selectedState_ = -1;       // into document_->states()
  int selectedTransition_ = -1;  // into document_->transitions()
  char renameInput_[64] = {}, newStateInput_[64] = "new_state", newTriggerInput_[64] = {};
  char savePathInput_[512] = "graph.json";
  int newExpression_ = 0, newFrom_ = 0, newTo_ = 0;
  // The transition editor's copy (committed when a drag ends or a box is ticked).
  GraphTransitionInfo editing_;
  float editingExit_ = 1.0f;
  bool editingHasExit_ = false;
  int editingIndex_ = -1;
  uint64_t editingRevision_ = 0;
};

}  // namespace editor
