#pragma once
// The state machine editor's model: a graph file (graph_json.h) held as its
// JSON, with typed edits of its state machine (states, transitions, their
// duration, easing, exit time and interruption rule), each one undoable.
// Keeping the document as JSON means saving writes exactly what the runtime's
// loader reads, and everything the editor does not edit (other nodes,
// timelines, blink, speech layers) is kept as it was.
//
// The state machine edited is the one named "emotions", else the first one
// found under "root" (depth first). A transition is addressed by FROM and TO:
// the first transition of state FROM (or of "any state", kAnyState) to TO.
// An edit that fails changes nothing and says why.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/json/json_document.h"

namespace editor {

struct GraphTransitionInfo {
  std::string from;  // kAnyState for an any-state transition
  std::string to;
  std::string trigger;  // the first trigger-style condition's parameter; "" when none
  float duration = 0.25f;
  std::string easing;  // "linear", "cosine", "smoothstep", "bezier", "keyed"
  std::optional<float> exitTime;
  bool interruptible = true;
};

struct GraphStateInfo {
  std::string name;
  std::string expression;  // the pose node's preset; "" when the state holds another node
};

// A transition's duration (finite, > 0) and easing name (linear, cosine, smoothstep: the
// named curves; Bezier and keyed curves stay as loaded until edited); the error says which is wrong.
eng::Result<void> checkTransitionTiming(float duration, std::string_view easing);

class GraphDocument {
 public:
  static constexpr std::string_view kAnyState = "any";

  // Fails when the document has no state machine (naming `source`).
  static eng::Result<GraphDocument> fromJson(facial::Json document, std::string source);
  static eng::Result<GraphDocument> load(const std::filesystem::path& path);

  const facial::Json& json() const { return document_; }
  const std::string& source() const { return source_; }
  std::vector<GraphStateInfo> states() const;
  std::vector<GraphTransitionInfo> transitions() const;
  std::optional<GraphTransitionInfo> findTransition(std::string_view from, std::string_view to) const;
  std::string defaultState() const;
  bool hasState(std::string_view name) const;

  // A state holding {"type": "pose", "preset": expression}.
  eng::Result<void> addState(std::string_view name, std::string_view expression);
  // Removes the state and every transition into it; the last state cannot go.
  eng::Result<void> removeState(std::string_view name);
  // Renames the state and every reference to it (transitions, defaultState).
  eng::Result<void> renameState(std::string_view from, std::string_view to);
  // trigger "" or "-": no condition; otherwise a trigger parameter, declared when missing.
  eng::Result<void> addTransition(std::string_view from, std::string_view to, std::string_view trigger, float duration,
                                  std::string_view easing);
  eng::Result<void> editTransition(std::string_view from, std::string_view to, float duration, std::string_view easing,
                                   std::optional<float> exitTime, bool interruptible);
  eng::Result<void> removeTransition(std::string_view from, std::string_view to);

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  bool undo();
  bool redo();
  // Undoes the last edit and forgets it (an edit the runtime then refused).
  void discardLast();

  // Writes the graph file whole (a failed save leaves the old file). Marks the document saved.
  eng::Result<void> save(const std::filesystem::path& path);
  // The same file, leaving the document unsaved (an autosave).
  eng::Result<void> writeCopy(const std::filesystem::path& path) const;
  bool dirty() const { return revision_ != savedRevision_; }
  // Changes with every edit, undo and redo.
  uint64_t revision() const { return revision_; }

 private:
  GraphDocument() = default;
  facial::Json& machine() { return document_.at(machinePointer_); }
  const facial::Json& machine() const { return document_.at(machinePointer_); }
  facial::Json* transitionList(std::string_view from);
  facial::Json* findTransitionJson(std::string_view from, std::string_view to);
  eng::Result<void> checkNewStateName(std::string_view name) const;
  eng::Result<void> declareTrigger(std::string_view trigger);
  struct Snapshot {
    facial::Json document;
    uint64_t revision = 0;
  };
  void commit(Snapshot before);
  Snapshot snapshot() const { return {document_, revision_}; }
  // Undo (undo_ -> redo_) or redo (redo_ -> undo_).
  bool step(std::vector<Snapshot>& from, std::vector<Snapshot>& to);

  facial::Json document_;
  facial::Json::json_pointer machinePointer_;
  std::string source_;
  std::vector<Snapshot> undo_, redo_;
  uint64_t revision_ = 0, savedRevision_ = 0, nextRevision_ = 1;
};

}  // namespace editor
