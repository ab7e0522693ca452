#pragma once
// Timeline panel: the keyframe editor over a TimelineDocument. Track list on
// the left, keys on a time ruler (height in a row = value), a playhead
// scrubbed in float time, play / pause / loop, add key at the playhead from
// the face on screen, select (ctrl: add) and drag keys in time and value,
// delete, per-key interpolation, undo / redo, open / save.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/face_setup.h"
#include "editor/app/face_delegate.h"
#include "editor/autosave.h"
#include "editor/timeline_document.h"
#include "editor/timeline_pose.h"
#include "editor/timeline_view.h"

namespace editor {

class TimelinePanel {
 public:
  TimelinePanel(const app::FaceSetup& face);
  // Unsaved edits stay in the autosave (the next open recovers them); a clean document removes it.
  ~TimelinePanel();
  TimelinePanel(const TimelinePanel&) = delete;
  TimelinePanel& operator=(const TimelinePanel&) = delete;
  // Opens a timeline file (errors shown in the panel and logged; the current document stays).
  // Unsaved edits an earlier editor autosaved for it are recovered instead, saying so.
  bool open(const std::string& path);
  bool save(const std::string& path);
  // Projects (editor/project.h): File > New starts an empty clip that saves
  // to `path`; the edits it replaces stay recoverable, as with open().
  void openEmpty(const std::string& path);
  // Quit > Discard: the unsaved edits and their autosave are dropped.
  void discardUnsavedEdits();
  const char* path() const { return path_; }
  // Writes unsaved edits to the autosave now (the window is going away on an
  // error) and says where they are, or why they could not be kept; empty when
  // there is nothing unsaved.
  std::string keepUnsavedEdits();

  void update(float dt);
  void draw(FaceDelegate& face);
  // Keyboard shortcuts (Ctrl+Z, Ctrl+Y, Delete, Space) when no text field has focus.
  void handleShortcuts();

  // The face posed by the document at the playhead.
  std::span<const float> targetWeights() const { return weights_; }
  std::span<const float> expressionWeights() const { return pose_.expressionWeights(); }
  TimelineDocument& document() { return document_; }
  float playhead() const { return playhead_; }
  void setPlayhead(float time);
  bool playing() const { return playing_; }
  void setPlaying(bool playing) { playing_ = playing; }
  // Play / pause (the button and Space); a once-only clip at its end restarts.
  void togglePlaying();

  // What the widgets and shortcuts do (the --script runs these too). Each
  // returns false after reporting why in the panel (and the log).
  // Scrubbing the ruler: the playhead stops there and the timeline drives the face.
  void seek(float time, FaceDelegate& face);
  // Clicking a track's name.
  bool selectTrack(std::string_view channel);
  // "Key track" / "Key all": keys at the playhead with the values on screen, selected.
  bool keyTrack(FaceDelegate& face) { return addKeys(face, false); }
  bool keyAll(FaceDelegate& face) { return addKeys(face, true); }
  // One drag of the selected keys by dt seconds and dv value (one undo step).
  bool moveSelected(float dt, float dv, FaceDelegate& face);
  bool deleteSelected();
  bool undo();
  bool redo();

 private:
  void drawToolbar(FaceDelegate& face);
  void drawFileAndTransport(FaceDelegate& face);
  void drawKeyAndTrackControls(FaceDelegate& face);
  void drawTracks(FaceDelegate& face);
  void drawTrackNames(const TimelineView& view, float left);
  void handleCanvasMouse(const TimelineView& view, FaceDelegate& face);
  void drawCanvas(const TimelineView& view);
  bool addKeys(FaceDelegate& face, bool allTracks);
  void refreshPose();
  void autosave();

  TimelineDocument document_;
  TimelinePose pose_;
  std::vector<float> weights_;
  uint64_t posedRevision_ = UINT64_MAX;
  float posedTime_ = -1.0f;
  float playhead_ = 0.0f;
  bool playing_ = false;
  float playTime_ = 0.0f;  // seconds played since the playhead was last set; the clip's loop mode maps it
  int currentTrack_ = -1;
  int newKeyInterpolation_ = 1;  // linear
  int channelChoice_ = 0;
  char path_[512] = "timeline.json";
  char channelFilter_[64] = {};
  // Drag state.
  bool draggingKeys_ = false;
  bool scrubbing_ = false;
  float dragStartX_ = 0.0f, dragStartY_ = 0.0f;
  PanelMessage message_;
  // Beside the document's path (editor/autosave.h); follows open and save.
  TimelineAutosave autosave_{autosavePathFor("timeline.json")};
  std::string autosaveError_;  // the last autosave failure reported (reported once)
};

}  // namespace editor
