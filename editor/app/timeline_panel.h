#pragma once
// Timeline panel: the keyframe editor over a TimelineDocument, two tabs over
// one time axis. The dope sheet: tracks grouped (brows, eyes, ..., the
// model's own targets; collapsible) with mute / solo, keys on a time ruler
// (height in a row = value), a playhead scrubbed on the ruler, box select
// (Shift extends, Ctrl toggles), drags snapped to frames, copy / paste /
// duplicate, nudge, zoom (wheel) and pan (middle drag), a loop range and a
// speed. The curves: editor/app/curve_panel.h. Keys: Space play, K key all,
// Delete, Ctrl+C/V/D/A, arrows nudge, Home/End, '.' frame selection.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_setup.h"
#include "editor/app/curve_panel.h"
#include "editor/app/editor_script.h"
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
  // Edit > Copy / Paste / Duplicate / Select all (and Ctrl+C / V / D / A): the
  // selected keys to the clipboard, pasted at `time`, duplicated a frame after.
  bool copySelection();
  bool pasteAt(float time);
  bool duplicateSelection() { return report(document_.duplicateSelected()); }
  void selectAll() { document_.selectAll(); }
  bool hasClipboard() const { return !clipboard_.empty(); }
  // The dope sheet's and curve view's script actions (editor_script.h, issue 34).
  bool runScriptAction(const EditorScriptAction& action, FaceDelegate& face);

 private:
  // Dope sheet and curve view actions: each reports why it failed.
  bool report(const eng::Result<void>& result);
  // The track of `channel`, or none after saying so.
  std::optional<size_t> trackNamed(std::string_view channel);
  bool boxSelect(float t0, float t1, std::span<const std::string> channels);
  bool toggleTrackFlag(std::string_view channel, bool solo);
  bool setCurveTangent(const std::string& channel, size_t index, CurveKeyMode mode, std::optional<float> in,
                       std::optional<float> out);
  bool keyEmotion(const std::string& emotion, float time, CurveKeyMode easing, FaceDelegate& face);
  void frameSelection();
  void frameAll();
  // The tracks the dope sheet hands the curve view: those with selected keys, else the current one.
  std::vector<size_t> curveTracks() const;
  void handleEditShortcuts();
  void drawViewControls();
  void drawStatus(FaceDelegate& face);
  void drawTrackName(size_t track, float left, float y);
  void drawGroupHeader(TrackGroup group, float left, float y);
  void handleCanvasWheelAndPan(const TimelineView& view);
  void finishBox(const TimelineView& view, const std::vector<TrackRow>& rows);
  void drawRuler(const TimelineView& view);
  void drawRows(const TimelineView& view, const std::vector<TrackRow>& rows);

  void drawToolbar(FaceDelegate& face);
  void drawFileAndTransport(FaceDelegate& face);
  void drawKeyAndTrackControls(FaceDelegate& face);
  void drawTracks(FaceDelegate& face);
  void drawTrackNames(const TimelineView& view, const std::vector<TrackRow>& rows, float left);
  void handleCanvasMouse(const TimelineView& view, const std::vector<TrackRow>& rows, FaceDelegate& face);
  // Hovering a key says its track, time, value and mode; the empty canvas, after a rest, how to use it.
  void tooltipForCanvas(const TimelineView& view, const std::vector<TrackRow>& rows);
  void drawCanvas(const TimelineView& view, const std::vector<TrackRow>& rows);
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
  std::optional<glm::vec2> boxStart_;  // a box selection being drawn
  bool panning_ = false;
  // The dope sheet's view and tools.
  TimeWindow window_{0.0f, 2.0f};
  bool showingAll_ = true;  // the window shows the whole clip (and follows its length)
  std::array<bool, kTrackGroupCount> collapsed_{};
  KeyClipboard clipboard_;
  bool snapping_ = true;  // key drags move by whole frames
  bool showCurves_ = false;  // a script's curve edit brings the curve tab up
  bool addKeysFromKeyboard_ = false;  // K was pressed (keyed in draw(), which has the face)
  CurvePanel curves_;
  std::vector<size_t> shownCurves_;  // the tracks the curve view overlays
  PanelMessage message_;
  // Beside the document's path (editor/autosave.h); follows open and save.
  TimelineAutosave autosave_{autosavePathFor("timeline.json")};
  std::string autosaveError_;  // the last autosave failure reported (reported once)
};

}  // namespace editor
