#include "editor/app/timeline_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>

#include <GLFW/glfw3.h>

#include "editor/app/editor_app.h"
#include "editor/app/tooltip.h"
#include "facial/runtime/graph/timeline.h"
#include "facial/runtime/rig/emotions.h"

namespace editor {

namespace {

constexpr const char* kInterpolationNames[] = {"step", "linear", "cosine", "cubic"};  // KeyInterpolation order
constexpr float kNameColumn = 170.0f;
constexpr float kRulerHeight = 20.0f;

bool textCaseInsensitiveContains(const std::string& text, const char* filter) {
  if (!filter[0]) return true;
  std::string a = text, b = filter;
  std::transform(a.begin(), a.end(), a.begin(), ::tolower);
  std::transform(b.begin(), b.end(), b.begin(), ::tolower);
  return a.find(b) != std::string::npos;
}

}  // namespace

TimelinePanel::TimelinePanel(const app::FaceSetup& face)
    : document_("untitled", 2.0f), pose_(face.rig(), face.baseWeights(), &face.expressions()), weights_(face.baseWeights().begin(), face.baseWeights().end()) {}

TimelinePanel::~TimelinePanel() {
  if (!document_.dirty()) {
    autosave_.discard();
  } else if (auto kept = autosave_.flush(document_); !kept) {
    fail(kept.error().message);
  }
}

bool TimelinePanel::open(const std::string& path) {
  auto recovered = recoverAutosave(path);
  if (!recovered) message_.report(recovered.error().message, true);  // the file itself still opens
  std::optional<RecoveredTimeline> recovery = recovered ? std::move(*recovered) : std::nullopt;
  auto loaded = recovery ? eng::Result<TimelineDocument>(std::move(recovery->document)) : TimelineDocument::load(path);
  if (!loaded) {
    message_.report(loaded.error().message, true);
    return false;
  }
  if (document_.dirty()) (void)autosave_.flush(document_);  // the edits being replaced stay recoverable
  document_ = std::move(*loaded);
  autosave_ = TimelineAutosave(autosavePathFor(path));
  autosaveError_.clear();
  std::snprintf(path_, sizeof path_, "%s", path.c_str());
  playTime_ = playhead_ = 0.0f;
  window_ = {0.0f, document_.duration()};
  currentTrack_ = document_.tracks().empty() ? -1 : 0;
  size_t unknown = 0;
  for (const DocumentTrack& track : document_.tracks())
    if (!pose_.knowsChannel(track.channel)) ++unknown;
  message_.report("opened " + path + " (" + std::to_string(document_.tracks().size()) + " tracks" +
                      (unknown ? ", " + std::to_string(unknown) + " on channels this face does not have" : std::string()) + ")",
                  false);
  if (recovery) message_.report(recovery->message, false);
  posedRevision_ = UINT64_MAX;
  return true;
}

bool TimelinePanel::save(const std::string& path) {
  if (auto saved = document_.save(path); !saved) {
    message_.report(saved.error().message, true);
    return false;
  }
  // Saved: the autosave of the old and of the new path hold nothing more.
  autosave_.discard();
  autosave_ = TimelineAutosave(autosavePathFor(path));
  autosave_.discard();
  autosaveError_.clear();
  message_.report("saved " + path, false);
  return true;
}

void TimelinePanel::openEmpty(const std::string& path) {
  if (document_.dirty()) (void)autosave_.flush(document_);
  document_ = TimelineDocument("untitled", 2.0f);
  autosave_ = TimelineAutosave(autosavePathFor(path));
  autosaveError_.clear();
  std::snprintf(path_, sizeof path_, "%s", path.c_str());
  playTime_ = playhead_ = 0.0f;
  currentTrack_ = -1;
  posedRevision_ = UINT64_MAX;
  message_.report("new clip (saves to " + path + ")", false);
}

void TimelinePanel::discardUnsavedEdits() {
  autosave_.discard();
  document_ = TimelineDocument("untitled", 2.0f);
  posedRevision_ = UINT64_MAX;
}

std::string TimelinePanel::keepUnsavedEdits() {
  if (!document_.dirty()) return {};
  if (auto kept = autosave_.flush(document_); !kept) return "unsaved timeline edits NOT kept: " + kept.error().message;
  return "unsaved timeline edits are in " + autosave_.file().string() + " (the next start recovers them)";
}

void TimelinePanel::autosave() {
  auto written = autosave_.update(document_, TimelineAutosave::Clock::now());
  if (written || written.error().message == autosaveError_) return;
  autosaveError_ = written.error().message;
  message_.report(autosaveError_, true);
}

void TimelinePanel::setPlayhead(float time) {
  if (std::isfinite(time)) playTime_ = playhead_ = std::clamp(time, 0.0f, document_.duration());
}

void TimelinePanel::togglePlaying() {
  playing_ = !playing_;
  // A clip that plays once and has reached its end starts again from the top.
  if (playing_ && document_.loop() == facial::LoopMode::Once && playhead_ >= document_.duration()) setPlayhead(0.0f);
}

void TimelinePanel::update(float dt) {
  if (playing_ && std::isfinite(dt)) {
    // Playback follows the clip's own loop mode, exactly as the runtime's timeline node plays it.
    // The loop range, when set, wraps playback inside it; the speed scales the clock.
    playTime_ += dt * document_.playback().speed;
    if (document_.loop() == facial::LoopMode::Once && !document_.playback().hasLoopRange &&
        playTime_ >= document_.duration())
      playing_ = false;
    playhead_ = document_.playheadAt(playTime_);
  }
  autosave();
  refreshPose();
}

void TimelinePanel::refreshPose() {
  if (posedRevision_ == document_.revision() && posedTime_ == playhead_) return;
  if (auto posed = pose_.pose(document_, playhead_, weights_); !posed) message_.report(posed.error().message, true);
  posedRevision_ = document_.revision();
  posedTime_ = playhead_;
}

void TimelinePanel::seek(float time, FaceDelegate& face) {
  setPlayhead(time);
  playing_ = false;
  face.takeControl(FaceSource::Timeline);
}

bool TimelinePanel::selectTrack(std::string_view channel) {
  const auto track = trackNamed(channel);
  if (!track) return false;
  currentTrack_ = int(*track);
  return true;
}

bool TimelinePanel::moveSelected(float dt, float dv, FaceDelegate& face) {
  if (document_.selection().empty()) {
    message_.report("no keys selected to move", true);
    return false;
  }
  if (auto moved = document_.moveSelectedBy(dt, dv); !moved) {
    message_.report(moved.error().message, true);
    return false;
  }
  face.takeControl(FaceSource::Timeline);
  return true;
}

bool TimelinePanel::deleteSelected() {
  if (document_.selection().empty()) {
    message_.report("no keys selected to delete", true);
    return false;
  }
  if (auto deleted = document_.deleteSelected(); !deleted) {
    message_.report(deleted.error().message, true);
    return false;
  }
  return true;
}

bool TimelinePanel::undo() {
  const std::string label(document_.undoLabel());
  if (!document_.undo()) {
    message_.report("nothing to undo", true);
    return false;
  }
  message_.report("undo: " + label, false);
  return true;
}

bool TimelinePanel::redo() {
  const std::string label(document_.redoLabel());
  if (!document_.redo()) {
    message_.report("nothing to redo", true);
    return false;
  }
  message_.report("redo: " + label, false);
  return true;
}

bool TimelinePanel::addKeys(FaceDelegate& face, bool allTracks) {
  const auto interpolation = facial::KeyInterpolation(newKeyInterpolation_);
  if (document_.tracks().empty() || (!allTracks && currentTrack_ < 0)) {
    message_.report("add a track first (pick a channel, then 'Add track')", true);
    return false;
  }
  std::vector<KeyId> added;
  const size_t first = allTracks ? 0 : size_t(currentTrack_);
  const size_t last = allTracks ? document_.tracks().size() : size_t(currentTrack_) + 1;
  for (size_t t = first; t < last; ++t) {
    const float value = face.currentValue(document_.tracks()[t].channel);
    auto key = document_.setKey(t, playhead_, value, interpolation);
    if (!key) {
      message_.report(key.error().message, true);
      return false;
    }
    added.push_back(*key);
  }
  document_.clearSelection();
  for (KeyId id : added) document_.select(id, true);
  return true;
}

void TimelinePanel::handleShortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  if (io.KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Z), false)) io.KeyShift ? redo() : undo();
  if (io.KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Y), false)) redo();
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete), false) && !document_.selection().empty()) deleteSelected();
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false) && !io.WantCaptureKeyboard) togglePlaying();
  handleEditShortcuts();
}

// The dope sheet's habits (Blender, Unity): copy / paste / duplicate / select all,
// arrows nudge the selection by a frame (without one, step the playhead),
// Home / End, K keys every track, '.' frames the selection.
void TimelinePanel::handleEditShortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  const auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
  if (io.KeyCtrl && pressed(GLFW_KEY_C)) copySelection();
  if (io.KeyCtrl && pressed(GLFW_KEY_V)) pasteAt(playhead_);
  if (io.KeyCtrl && pressed(GLFW_KEY_D)) duplicateSelection();
  if (io.KeyCtrl && pressed(GLFW_KEY_A)) selectAll();
  for (const auto& [key, frames] : {std::pair{GLFW_KEY_LEFT, -1}, std::pair{GLFW_KEY_RIGHT, 1}}) {
    if (!ImGui::IsKeyPressed(key, true)) continue;
    const int step = io.KeyShift ? 10 * frames : frames;
    if (!document_.selection().empty()) report(document_.nudgeSelected(step));
    else setPlayhead(document_.snapTime(playhead_) + float(step) * document_.frameDuration());
  }
  const PlaybackSettings& p = document_.playback();
  if (pressed(GLFW_KEY_HOME)) setPlayhead(p.hasLoopRange ? p.loopStart : 0.0f);
  if (pressed(GLFW_KEY_END)) setPlayhead(p.hasLoopRange ? p.loopEnd : document_.duration());
  if (!io.KeyCtrl && pressed(GLFW_KEY_K)) addKeysFromKeyboard_ = true;
  if (pressed(GLFW_KEY_PERIOD)) frameSelection();
}

void TimelinePanel::drawToolbar(FaceDelegate& face) {
  drawFileAndTransport(face);
  drawKeyAndTrackControls(face);
}

// The first toolbar row: open / save, play, loop mode, playhead, length, undo / redo.
void TimelinePanel::drawFileAndTransport(FaceDelegate& face) {
  // Files.
  ImGui::SetNextItemWidth(220.0f);
  ImGui::InputText("##path", path_, sizeof path_);
  tooltip("The timeline file Open reads and Save writes (JSON, as facial play reads it)");
  ImGui::SameLine();
  if (ImGui::Button("Open")) open(path_);
  tooltip("Open the timeline file named on the left (unsaved edits stay in their autosave)");
  ImGui::SameLine();
  if (ImGui::Button(document_.dirty() ? "Save*" : "Save")) save(path_);
  tooltip("Save the clip to the file named on the left (* : unsaved edits; File > Save, Ctrl+S, saves the whole project)");
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  // Transport.
  if (ImGui::Button("|<")) setPlayhead(0.0f);
  tooltip("Playhead to the start (Home; End: to the end)");
  ImGui::SameLine();
  if (ImGui::Button(playing_ ? "Pause" : "Play", {52.0f, 0.0f})) {
    togglePlaying();
    if (playing_) face.takeControl(FaceSource::Timeline);
  }
  tooltip("Play / pause the clip on the face (Space)");
  ImGui::SameLine();
  // The clip's loop mode (saved with it, undoable): how the runtime plays it past its end.
  static constexpr const char* kLoopModes[] = {"once", "loop", "ping-pong"};
  static constexpr facial::LoopMode kLoopValues[] = {facial::LoopMode::Once, facial::LoopMode::Loop,
                                                     facial::LoopMode::PingPong};
  int loopChoice = int(std::find(std::begin(kLoopValues), std::end(kLoopValues), document_.loop()) - std::begin(kLoopValues));
  ImGui::SetNextItemWidth(90.0f);
  if (ImGui::Combo("##loop", &loopChoice, kLoopModes, 3)) (void)document_.setLoop(kLoopValues[loopChoice]);
  tooltip("How the clip plays past its end: once, loop or ping-pong (saved with it; the runtime plays it so)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70.0f);
  float time = playhead_;
  if (ImGui::DragFloat("##time", &time, 0.01f, 0.0f, document_.duration(), "%.2f s")) {
    setPlayhead(time);
    face.takeControl(FaceSource::Timeline);
  }
  tooltip("The playhead (drag, or double-click to type; Left / Right step a frame)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70.0f);
  float duration = document_.duration();
  if (ImGui::DragFloat("length", &duration, 0.01f, TimelineDocument::kMinDuration, 600.0f, "%.2f s")) {
    if (auto set = document_.setDuration(duration); !set) message_.report(set.error().message, true);
  }
  tooltip("The clip's length in seconds (drag, or double-click to type)");
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  if (!document_.canUndo()) ImGui::BeginDisabled();
  if (ImGui::Button("Undo")) undo();
  tooltip(document_.canUndo() ? "Undo: " + std::string(document_.undoLabel()) + " (Ctrl+Z)" : std::string("Nothing to undo (Ctrl+Z)"));
  if (!document_.canUndo()) ImGui::EndDisabled();
  ImGui::SameLine();
  if (!document_.canRedo()) ImGui::BeginDisabled();
  if (ImGui::Button("Redo")) redo();
  tooltip(document_.canRedo() ? "Redo: " + std::string(document_.redoLabel()) + " (Ctrl+Y, Ctrl+Shift+Z)" : std::string("Nothing to redo (Ctrl+Y)"));
  if (!document_.canRedo()) ImGui::EndDisabled();
}

// The second toolbar row: keying, the selected keys' interpolation, adding and removing tracks.
void TimelinePanel::drawKeyAndTrackControls(FaceDelegate& face) {
  // Keys.
  if (ImGui::Button("Key track")) keyTrack(face);
  tooltip("Key the selected track at the playhead with the value on screen");
  ImGui::SameLine();
  if (ImGui::Button("Key all")) keyAll(face);
  tooltip("Key every track at the playhead with the values on screen (K)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80.0f);
  ImGui::Combo("new keys", &newKeyInterpolation_, kInterpolationNames, 4);
  tooltip("The interpolation Key track, Key all and K give new keys");
  ImGui::SameLine();
  const bool hasSelection = !document_.selection().empty();
  if (!hasSelection) ImGui::BeginDisabled();
  if (ImGui::Button("Delete")) deleteSelected();
  tooltip("Delete the selected keys (Delete)");
  ImGui::SameLine();
  int selectedInterpolation = -1;
  if (hasSelection)
    if (const DocumentKey* k = document_.key(document_.selection().front())) selectedInterpolation = int(k->key.interpolation);
  ImGui::SetNextItemWidth(80.0f);
  if (ImGui::Combo("selected", &selectedInterpolation, kInterpolationNames, 4))
    (void)document_.setSelectedInterpolation(facial::KeyInterpolation(selectedInterpolation));
  tooltip("The selected keys' interpolation (the segment each starts; the Curves tab sets tangents)");
  if (!hasSelection) ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  // Tracks.
  const auto channels = pose_.channelNames();
  channelChoice_ = std::clamp(channelChoice_, 0, int(channels.size()) - 1);
  ImGui::SetNextItemWidth(190.0f);
  const bool choosing = ImGui::BeginCombo("##channel", channels.empty() ? "" : channels[size_t(channelChoice_)].c_str());
  if (!choosing) tooltip("The channel Add track adds: an action unit, an emotion, a viseme or one of the model's targets");
  if (choosing) {
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::InputTextWithHint("##filter", "filter", channelFilter_, sizeof channelFilter_);
    tooltip("Show only the channels whose name holds this text");
    for (size_t c = 0; c < channels.size(); ++c) {
      if (!textCaseInsensitiveContains(channels[c], channelFilter_)) continue;
      const bool used = document_.findTrack(channels[c]).has_value();
      if (ImGui::Selectable(channels[c].c_str(), int(c) == channelChoice_, used ? ImGuiSelectableFlags_Disabled : 0))
        channelChoice_ = int(c);
      tooltip(used ? "The clip has a track on this channel already" : "Pick this channel for Add track");
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (ImGui::Button("Add track") && !channels.empty()) {
    auto added = document_.addTrack(channels[size_t(channelChoice_)]);
    if (added) currentTrack_ = int(*added);
    else message_.report(added.error().message, true);
  }
  tooltip("Add a track on the channel picked on the left");
  ImGui::SameLine();
  if (currentTrack_ < 0) ImGui::BeginDisabled();
  if (ImGui::Button("Remove track") && currentTrack_ >= 0) {
    (void)document_.removeTrack(size_t(currentTrack_));
    currentTrack_ = std::min(currentTrack_, int(document_.tracks().size()) - 1);
  }
  tooltip("Remove the current track and its keys (undoable)");
  if (currentTrack_ < 0) ImGui::EndDisabled();
}

void TimelinePanel::drawTracks(FaceDelegate& face) {
  ImGui::BeginChild("tracks", {0.0f, 0.0f}, true);
  const auto tracks = document_.tracks();
  if (currentTrack_ >= int(tracks.size())) currentTrack_ = int(tracks.size()) - 1;
  const std::vector<TrackRow> rows = layoutTrackRows(tracks, collapsed_);
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  if (showingAll_) window_ = {0.0f, document_.duration()};  // the whole clip follows its length
  window_.clampTo(document_.duration());
  TimelineView view = TimelineView::fit(
      {.left = origin.x, .top = origin.y, .width = avail.x, .height = avail.y, .nameColumn = kNameColumn, .rulerHeight = kRulerHeight},
      rows.size(), document_.duration(), document_.minValue(), document_.maxValue());
  view.showTime(window_);
  drawTrackNames(view, rows, origin.x);
  // The key canvas: one invisible button takes every click on ruler and rows.
  ImGui::SetCursorScreenPos({view.canvasLeft(), view.top()});
  ImGui::InvisibleButton("canvas", {view.canvasWidth(), view.canvasHeight()},
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonMiddle);
  handleCanvasMouse(view, rows, face);
  tooltipForCanvas(view, rows);
  drawCanvas(view, rows);
  ImGui::EndChild();
}

void TimelinePanel::drawTrackNames(const TimelineView& view, const std::vector<TrackRow>& rows, float left) {
  for (size_t r = 0; r < rows.size(); ++r) {
    const float y = view.rowTop(r) + (view.rowHeight() - ImGui::GetFrameHeight()) * 0.5f;
    if (rows[r].track) drawTrackName(*rows[r].track, left, y);
    else drawGroupHeader(rows[r].group, left, y);
  }
}

void TimelinePanel::drawGroupHeader(TrackGroup group, float left, float y) {
  ImGui::SetCursorScreenPos({left, y});
  ImGui::PushID(int(group) + 100000);
  bool& collapsed = collapsed_[size_t(group)];
  if (ImGui::ArrowButton("##fold", collapsed ? ImGuiDir_Right : ImGuiDir_Down)) collapsed = !collapsed;
  tooltip(collapsed ? "Show the group's tracks" : "Fold the group's tracks away");
  ImGui::SameLine();
  ImGui::AlignTextToFramePadding();
  ImGui::TextDisabled("%.*s", int(trackGroupName(group).size()), trackGroupName(group).data());
  ImGui::PopID();
}

// A track's name (click: current track; Ctrl+click or double-click: all its
// keys selected, Shift adds them) and its M(ute) / S(olo) toggles.
void TimelinePanel::drawTrackName(size_t t, float left, float y) {
  const DocumentTrack& track = document_.tracks()[t];
  ImGui::SetCursorScreenPos({left + 8.0f, y});
  ImGui::PushID(int(t));
  const bool known = pose_.knowsChannel(track.channel);
  if (!known || !document_.audible(t))
    ImGui::PushStyleColor(ImGuiCol_Text, known ? ImVec4(0.5f, 0.5f, 0.55f, 1.0f) : ImVec4(1.0f, 0.6f, 0.4f, 1.0f));
  if (ImGui::Selectable(track.channel.c_str(), currentTrack_ == int(t), ImGuiSelectableFlags_AllowDoubleClick,
                        {kNameColumn - 62.0f, ImGui::GetFrameHeight()})) {
    currentTrack_ = int(t);
    const ImGuiIO& io = ImGui::GetIO();
    if (io.KeyCtrl || ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
      std::vector<KeyId> ids;
      for (const DocumentKey& k : track.keys) ids.push_back(k.id);
      document_.selectKeys(ids, io.KeyShift ? SelectMode::Extend : SelectMode::Replace);
    }
  }
  if (!known || !document_.audible(t)) ImGui::PopStyleColor();
  tooltip((known ? std::string() : "This face has no channel '" + track.channel + "'.\n") +
          "Click: the current track (Key track keys it). Ctrl+click or double-click: select all its keys (Shift adds)");
  for (const bool solo : {false, true}) {
    ImGui::SameLine(0.0f, 2.0f);
    const bool on = solo ? track.solo : track.muted;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, solo ? ImVec4(0.8f, 0.65f, 0.1f, 1.0f) : ImVec4(0.7f, 0.2f, 0.2f, 1.0f));
    if (ImGui::SmallButton(solo ? "S" : "M")) toggleTrackFlag(track.channel, solo);
    if (on) ImGui::PopStyleColor();
    tooltip(solo ? "Solo: preview only the soloed tracks" : "Mute: leave this track out of the preview (still saved)");
  }
  ImGui::PopID();
}

// Wheel: zoom about the mouse; middle drag: pan.
void TimelinePanel::handleCanvasWheelAndPan(const TimelineView& view) {
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsItemHovered() && io.MouseWheel != 0.0f) {
    window_.zoom(view.timeAt(io.MousePos.x), std::pow(1.2f, io.MouseWheel));
    showingAll_ = false;
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Middle)) {
    window_.pan(-view.secondsFor(io.MouseDelta.x));
    showingAll_ = false;
    panning_ = true;
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Middle)) panning_ = false;
}

// The canvas button's clicks and drags: the ruler scrubs (Alt: selects the
// keys at that time); a key is selected (Ctrl or Shift: toggled) and drags the
// selection, by whole frames while snapping; empty rows start a box (Shift
// extends, Ctrl toggles; a click without a drag clears the selection).
void TimelinePanel::handleCanvasMouse(const TimelineView& view, const std::vector<TrackRow>& rows, FaceDelegate& face) {
  handleCanvasWheelAndPan(view);
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 mouse = io.MousePos;
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    const auto hit = view.hitAt(document_.tracks(), rows, {mouse.x, mouse.y});
    if (hit && rows[hit->row].track) currentTrack_ = int(*rows[hit->row].track);
    if (!hit && io.KeyAlt) {
      document_.selectAtTime(view.timeAt(mouse.x), io.KeyShift ? SelectMode::Extend : SelectMode::Replace);
    } else if (hit && hit->key) {
      const KeyId key = *hit->key;
      if (io.KeyCtrl || io.KeyShift) document_.select(key, true);
      else if (!document_.isSelected(key)) document_.select(key);
      if (document_.isSelected(key)) {
        document_.beginMove();
        draggingKeys_ = true;
        dragStartX_ = mouse.x;
        dragStartY_ = mouse.y;
      }
    } else if (hit) {
      boxStart_ = glm::vec2(mouse.x, mouse.y);
    } else {
      scrubbing_ = true;
    }
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    if (draggingKeys_) {
      float dt = view.secondsFor(mouse.x - dragStartX_);
      if (snapping_) dt = document_.snapTime(dt);
      document_.moveSelected(dt, view.valueFor(mouse.y - dragStartY_));
      face.takeControl(FaceSource::Timeline);
    } else if (scrubbing_) {
      seek(view.timeAt(mouse.x), face);
    }
  } else {
    if (draggingKeys_) document_.endMove();
    if (boxStart_) finishBox(view, rows);
    draggingKeys_ = false;
    scrubbing_ = false;
  }
}

void TimelinePanel::tooltipForCanvas(const TimelineView& view, const std::vector<TrackRow>& rows) {
  if (draggingKeys_ || scrubbing_ || panning_ || boxStart_) return;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (const auto hit = view.hitAt(document_.tracks(), rows, {mouse.x, mouse.y}); hit && hit->key && rows[hit->row].track)
    if (const DocumentKey* k = document_.key(*hit->key))
      return tooltip(keyHoverText(document_.tracks()[*rows[hit->row].track].channel, k->key, document_.frameRate()));
  tooltip("Click a key: select (Shift / Ctrl: add / toggle), drag: move. Drag on empty rows: box select.\n"
          "Ruler: scrub (Alt+click: the keys at that time). Wheel: zoom, middle drag: pan.\n"
          "Space play, K key all, Delete, Ctrl+C / V / D / A, Left / Right nudge, Home / End",
          kCanvasHelpDelay);
}

void TimelinePanel::finishBox(const TimelineView& view, const std::vector<TrackRow>& rows) {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 a = *boxStart_, b{io.MousePos.x, io.MousePos.y};
  boxStart_.reset();
  const SelectMode mode = io.KeyCtrl ? SelectMode::Toggle : io.KeyShift ? SelectMode::Extend : SelectMode::Replace;
  if (glm::length(b - a) < 3.0f) {  // a click, not a box
    if (mode == SelectMode::Replace) document_.clearSelection();
    return;
  }
  // The tracks of the rows the box spans; a group header takes its group's tracks.
  std::vector<size_t> tracks;
  const size_t first = view.rowAt(std::min(a.y, b.y)).value_or(0);
  const size_t last = view.rowAt(std::max(a.y, b.y)).value_or(rows.empty() ? 0 : rows.size() - 1);
  for (size_t r = first; r <= last && r < rows.size(); ++r) {
    if (rows[r].track) tracks.push_back(*rows[r].track);
    else
      for (size_t t = 0; t < document_.tracks().size(); ++t)
        if (trackGroupOf(document_.tracks()[t].channel) == rows[r].group) tracks.push_back(t);
  }
  if (tracks.empty()) return;
  document_.selectBox(view.timeAt(a.x), view.timeAt(b.x), tracks, mode);
}

void TimelinePanel::drawRuler(const TimelineView& view) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = view.canvasLeft(), right = view.canvasRight(), top = view.top(), rowsTop = view.rowsTop();
  draw->AddRectFilled({left, top}, {right, rowsTop}, IM_COL32(40, 44, 54, 255));
  const PlaybackSettings& p = document_.playback();
  if (p.hasLoopRange)
    draw->AddRectFilled({std::max(view.xAt(p.loopStart), left), top}, {std::min(view.xAt(p.loopEnd), right), rowsTop},
                        IM_COL32(70, 110, 70, 255));
  // Five ticks per label, labels every rulerLabelStep() of the shown span.
  const float labelStep = TimelineView::rulerLabelStep(view.timeEnd() - view.timeStart());
  const float tickStep = (view.timeEnd() - view.timeStart() < 0.6f ? 0.1f : labelStep) / 5.0f;
  for (int i = int(std::ceil(std::max(view.timeStart(), 0.0f) / tickStep));; ++i) {
    const float t = float(i) * tickStep, x = view.xAt(t);
    if (x > right || t > document_.duration() + 1e-4f) break;
    const bool major = i % 5 == 0;
    draw->AddLine({x, rowsTop - (major ? 10.0f : 5.0f)}, {x, rowsTop}, IM_COL32(150, 150, 160, 255));
    if (!major) continue;
    char label[16];
    std::snprintf(label, sizeof label, tickStep < 0.05f ? "%.2f" : "%.1f", double(t));
    const float width = ImGui::CalcTextSize(label).x;
    draw->AddText({x + 2.0f + width > right ? x - 2.0f - width : x + 2.0f, top + 1.0f}, IM_COL32(190, 190, 200, 255), label);
    draw->AddLine({x, rowsTop}, {x, view.rowsBottom()}, IM_COL32(55, 60, 72, 255));
  }
}

void TimelinePanel::drawRows(const TimelineView& view, const std::vector<TrackRow>& rows) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = view.canvasLeft(), right = view.canvasRight();
  for (size_t r = 0; r < rows.size(); ++r) {
    const float rowTop = view.rowTop(r);
    if (!rows[r].track) {
      draw->AddRectFilled({left, rowTop}, {right, rowTop + view.rowHeight() - 1.0f}, IM_COL32(26, 28, 34, 255));
      continue;
    }
    const size_t t = *rows[r].track;
    const DocumentTrack& track = document_.tracks()[t];
    draw->AddRectFilled({left, rowTop}, {right, rowTop + view.rowHeight() - 1.0f},
                        int(t) == currentTrack_ ? IM_COL32(44, 52, 70, 255) : (r % 2 ? IM_COL32(32, 35, 42, 255) : IM_COL32(36, 39, 47, 255)));
    if (track.keys.empty()) continue;
    const ImU32 curve = document_.audible(t) ? IM_COL32(110, 170, 230, 200) : IM_COL32(90, 90, 100, 160);
    ImVec2 previous{left, view.yAt(r, document_.sample(t, view.timeAt(left)))};
    for (float x = left + 3.0f; x <= right; x += 3.0f) {
      const ImVec2 p{x, view.yAt(r, document_.sample(t, view.timeAt(x)))};
      draw->AddLine(previous, p, curve, 1.5f);
      previous = p;
    }
    for (const DocumentKey& k : track.keys) {
      const ImVec2 c{view.xAt(k.key.time), view.yAt(r, k.key.value)};
      const float s = 5.0f;
      const ImU32 colour = document_.isSelected(k.id) ? IM_COL32(255, 180, 60, 255) : IM_COL32(225, 225, 235, 255);
      if (k.key.interpolation == facial::KeyInterpolation::Step)
        draw->AddRectFilled({c.x - s + 1, c.y - s + 1}, {c.x + s - 1, c.y + s - 1}, colour);
      else if (k.key.interpolation == facial::KeyInterpolation::Linear)
        draw->AddQuadFilled({c.x, c.y - s}, {c.x + s, c.y}, {c.x, c.y + s}, {c.x - s, c.y}, colour);
      else
        draw->AddCircleFilled(c, s - 0.5f, colour, 12);
    }
  }
}

void TimelinePanel::drawCanvas(const TimelineView& view, const std::vector<TrackRow>& rows) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = view.canvasLeft(), right = view.canvasRight(), top = view.top();
  draw->PushClipRect({left, top}, {right, view.top() + view.canvasHeight()}, true);
  drawRuler(view);
  drawRows(view, rows);
  // The clip's end (the window may show past it) and the loop range's edges.
  const float end = view.xAt(document_.duration());
  draw->AddRectFilled({end, view.rowsTop()}, {right, view.rowsBottom()}, IM_COL32(0, 0, 0, 90));
  const PlaybackSettings& p = document_.playback();
  if (p.hasLoopRange)
    for (const float t : {p.loopStart, p.loopEnd})
      draw->AddLine({view.xAt(t), top}, {view.xAt(t), view.rowsBottom()}, IM_COL32(110, 200, 110, 200), 1.0f);
  const float px = view.xAt(playhead_);
  draw->AddLine({px, top}, {px, view.rowsBottom()}, IM_COL32(255, 80, 80, 255), 2.0f);
  draw->AddTriangleFilled({px - 6, top}, {px + 6, top}, {px, top + 8}, IM_COL32(255, 80, 80, 255));
  if (boxStart_) {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    draw->AddRectFilled({boxStart_->x, boxStart_->y}, mouse, IM_COL32(120, 160, 255, 40));
    draw->AddRect({boxStart_->x, boxStart_->y}, mouse, IM_COL32(120, 160, 255, 200));
  }
  if (document_.tracks().empty())
    draw->AddText({left + 10.0f, view.rowsTop() + 8.0f}, IM_COL32(160, 160, 170, 255),
                  "No tracks: pick a channel above and press 'Add track', or open a timeline file.");
  draw->PopClipRect();
}

// The view row: time axis, frames, loop range, speed, then the status.
void TimelinePanel::drawViewControls() {
  if (ImGui::SmallButton("Frame all")) frameAll();
  tooltip("Show the whole clip (wheel: zoom, middle drag: pan)");
  ImGui::SameLine();
  if (ImGui::SmallButton("Frame sel.")) frameSelection();
  tooltip("Show the selected keys ('.')");
  ImGui::SameLine();
  ImGui::Checkbox("snap", &snapping_);
  tooltip("Key drags move by whole frames");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(50.0f);
  float fps = document_.frameRate();
  if (ImGui::InputFloat("fps", &fps, 0.0f, 0.0f, "%.0f", ImGuiInputTextFlags_EnterReturnsTrue)) report(document_.snapToFrames(fps));
  tooltip("Frame rate of nudges and snapping; Enter also snaps the selected keys (all if none)");
  ImGui::SameLine();
  const PlaybackSettings p = document_.playback();
  if (ImGui::SmallButton(p.hasLoopRange ? "Clear loop" : "Loop sel.")) {
    if (p.hasLoopRange) report(document_.clearLoopRange());
    else if (!document_.selection().empty()) {
      float first = document_.duration(), last = 0.0f;
      for (KeyId id : document_.selection()) first = std::min(first, document_.key(id)->key.time), last = std::max(last, document_.key(id)->key.time);
      report(document_.setLoopRange(first, last));
    }
  }
  tooltip("Loop playback over the selected keys' times (green on the ruler)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(60.0f);
  float speed = p.speed;
  if (ImGui::InputFloat("speed", &speed, 0.0f, 0.0f, "%.2fx", ImGuiInputTextFlags_EnterReturnsTrue)) report(document_.setSpeed(speed));
  tooltip("Playback speed (Enter sets it; a preview setting, kept in the project, not in the clip file)");
  ImGui::SameLine();
}

void TimelinePanel::draw(FaceDelegate& face) {
  drawToolbar(face);
  if (addKeysFromKeyboard_) keyAll(face);
  addKeysFromKeyboard_ = false;
  if (ImGui::BeginTabBar("timeline views")) {
    const bool dopeSheet = ImGui::BeginTabItem("Dope sheet");
    tooltip("Keys on rows, one per track, grouped (select, move, copy, paste, nudge)");
    if (dopeSheet) {
      drawViewControls();
      drawStatus(face);
      drawTracks(face);
      if (!showCurves_) shownCurves_ = curveTracks();  // picked in the dope sheet; clicks in the curve view keep them
      ImGui::EndTabItem();
    }
    const bool curves = ImGui::BeginTabItem("Curves", nullptr, showCurves_ ? ImGuiTabItemFlags_SetSelected : 0);
    tooltip("The selected keys' tracks as curves, with tangent handles");
    if (curves) {
      curves_.draw(document_, shownCurves_, window_, playhead_);
      ImGui::EndTabItem();
    }
    showCurves_ = false;
    ImGui::EndTabBar();
  }
  refreshPose();
}

void TimelinePanel::drawStatus(FaceDelegate& face) {
  char status[160];
  std::snprintf(status, sizeof status, "%s%s  %zu tracks  %zu selected  %s", document_.name().c_str(),
                document_.dirty() ? " (modified)" : "", document_.tracks().size(), document_.selection().size(),
                face.source() == FaceSource::Timeline ? "drives the face" : "");
  ImGui::TextDisabled("%s", status);
  if (!message_.text.empty()) {
    ImGui::SameLine();
    message_.draw();
  }
}

// ---- Dope sheet and curve view actions (the keys, the widgets and the script) ----

bool TimelinePanel::report(const eng::Result<void>& result) {
  if (!result) message_.report(result.error().message, true);
  return result.ok();
}

std::vector<size_t> TimelinePanel::curveTracks() const {
  std::vector<size_t> shown;
  for (size_t t = 0; t < document_.tracks().size(); ++t)
    for (const DocumentKey& k : document_.tracks()[t].keys)
      if (document_.isSelected(k.id)) {
        shown.push_back(t);
        break;
      }
  if (shown.empty() && currentTrack_ >= 0 && size_t(currentTrack_) < document_.tracks().size()) shown.push_back(size_t(currentTrack_));
  return shown;
}

void TimelinePanel::frameAll() {
  window_ = {0.0f, document_.duration()};
  showingAll_ = true;
}

void TimelinePanel::frameSelection() {
  if (document_.selection().empty()) return frameAll();
  float first = document_.duration(), last = 0.0f;
  for (KeyId id : document_.selection())
    if (const DocumentKey* k = document_.key(id)) first = std::min(first, k->key.time), last = std::max(last, k->key.time);
  window_.frame(first, last);
  showingAll_ = false;
}

std::optional<size_t> TimelinePanel::trackNamed(std::string_view channel) {
  const auto track = document_.findTrack(channel);
  if (!track) message_.report("no track on channel '" + std::string(channel) + "'", true);
  return track;
}

bool TimelinePanel::boxSelect(float t0, float t1, std::span<const std::string> channels) {
  std::vector<size_t> tracks;
  for (const std::string& channel : channels) {
    const auto track = trackNamed(channel);
    if (!track) return false;
    tracks.push_back(*track);
  }
  document_.selectBox(t0, t1, tracks, SelectMode::Replace);
  return true;
}

bool TimelinePanel::copySelection() {
  if (document_.selection().empty()) {
    message_.report("no keys selected to copy", true);
    return false;
  }
  clipboard_ = document_.copySelection();
  message_.report("copied " + std::to_string(clipboard_.keys.size()) + " keys", false);
  return true;
}

bool TimelinePanel::pasteAt(float time) { return report(document_.paste(clipboard_, time)); }

bool TimelinePanel::toggleTrackFlag(std::string_view channel, bool solo) {
  const auto track = trackNamed(channel);
  if (!track) return false;
  const DocumentTrack& t = document_.tracks()[*track];
  return report(solo ? document_.setSolo(*track, !t.solo) : document_.setMuted(*track, !t.muted));
}

bool TimelinePanel::setCurveTangent(const std::string& channel, size_t index, CurveKeyMode mode, std::optional<float> in,
                                    std::optional<float> out) {
  const auto track = trackNamed(channel);
  if (!track) return false;
  if (index >= document_.tracks()[*track].keys.size()) {
    message_.report("track '" + channel + "' has " + std::to_string(document_.tracks()[*track].keys.size()) +
                        " keys, no key " + std::to_string(index),
                    true);
    return false;
  }
  const KeyId id = document_.tracks()[*track].keys[index].id;
  if (std::find(shownCurves_.begin(), shownCurves_.end(), *track) == shownCurves_.end()) shownCurves_.push_back(*track);
  document_.select(id);
  currentTrack_ = int(*track);
  showCurves_ = true;  // as a person would: the curve tab, this key selected
  return report(setCurveKeyMode(document_, id, mode, in, out));
}

bool TimelinePanel::keyEmotion(const std::string& emotion, float time, CurveKeyMode easing, FaceDelegate& face) {
  const CurveKeyShape shape = curveKeyShape(easing);
  if (!report(document_.keyExclusive(emotion, facial::emotionNames(), time, shape.interpolation, shape.tangent))) return false;
  currentTrack_ = int(*document_.findTrack(emotion));
  face.takeControl(FaceSource::Timeline);
  return true;
}

bool TimelinePanel::runScriptAction(const EditorScriptAction& a, FaceDelegate& face) {
  using Kind = EditorScriptAction::Kind;
  switch (a.kind) {
    case Kind::TimelineBoxSelect: return boxSelect(a.a, a.b, a.words);
    case Kind::TimelineCopy: return copySelection();
    case Kind::TimelinePaste: return pasteAt(a.a);
    case Kind::TimelineDuplicate: return duplicateSelection();
    case Kind::TimelineNudge: return report(document_.nudgeSelected(int(a.a)));
    case Kind::TimelineSnap: return report(document_.snapToFrames(a.a));
    case Kind::TimelineLoop: return report(document_.setLoopRange(a.a, a.b));
    case Kind::TimelineSpeed: return report(document_.setSpeed(a.a));
    case Kind::TimelineMute: return toggleTrackFlag(a.text, false);
    case Kind::TimelineSolo: return toggleTrackFlag(a.text, true);
    case Kind::CurveTangent:
      return setCurveTangent(a.words[0], size_t(a.a), *curveKeyModeFromName(a.words[1]),
                             a.numberCount == 3 ? std::optional(a.b) : std::nullopt,
                             a.numberCount == 3 ? std::optional(a.c) : std::nullopt);
    case Kind::TimelineKeyEmotion: return keyEmotion(a.words[0], a.a, *curveKeyModeFromName(a.words[1]), face);
    case Kind::TimelinePlay:  // the Play button (Space)
      if (!playing_) togglePlaying();
      face.takeControl(FaceSource::Timeline);
      return true;
    case Kind::TimelinePause:
      playing_ = false;
      return true;
    default: return false;
  }
}

}  // namespace editor
