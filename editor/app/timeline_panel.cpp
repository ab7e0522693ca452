#include "editor/app/timeline_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>

#include "editor/app/editor_app.h"
#include "facial/runtime/graph/timeline.h"

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
    : document_("untitled", 2.0f), pose_(face.rig(), face.baseWeights()), weights_(face.baseWeights().begin(), face.baseWeights().end()) {}

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
    playTime_ += dt;
    const facial::LoopMode mode = document_.loop();
    if (mode == facial::LoopMode::Once && playTime_ >= document_.duration()) playing_ = false;
    playhead_ = facial::clipTime(mode, document_.duration(), playTime_);
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
  const auto track = document_.findTrack(channel);
  if (!track) {
    message_.report("no track on channel '" + std::string(channel) + "'", true);
    return false;
  }
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
  ImGui::SameLine();
  if (ImGui::Button("Open")) open(path_);
  ImGui::SameLine();
  if (ImGui::Button(document_.dirty() ? "Save*" : "Save")) save(path_);
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  // Transport.
  if (ImGui::Button("|<")) setPlayhead(0.0f);
  ImGui::SameLine();
  if (ImGui::Button(playing_ ? "Pause" : "Play", {52.0f, 0.0f})) {
    togglePlaying();
    if (playing_) face.takeControl(FaceSource::Timeline);
  }
  ImGui::SameLine();
  // The clip's loop mode (saved with it, undoable): how the runtime plays it past its end.
  static constexpr const char* kLoopModes[] = {"once", "loop", "ping-pong"};
  static constexpr facial::LoopMode kLoopValues[] = {facial::LoopMode::Once, facial::LoopMode::Loop,
                                                     facial::LoopMode::PingPong};
  int loopChoice = int(std::find(std::begin(kLoopValues), std::end(kLoopValues), document_.loop()) - std::begin(kLoopValues));
  ImGui::SetNextItemWidth(90.0f);
  if (ImGui::Combo("##loop", &loopChoice, kLoopModes, 3)) (void)document_.setLoop(kLoopValues[loopChoice]);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70.0f);
  float time = playhead_;
  if (ImGui::DragFloat("##time", &time, 0.01f, 0.0f, document_.duration(), "%.2f s")) {
    setPlayhead(time);
    face.takeControl(FaceSource::Timeline);
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70.0f);
  float duration = document_.duration();
  if (ImGui::DragFloat("length", &duration, 0.01f, TimelineDocument::kMinDuration, 600.0f, "%.2f s")) {
    if (auto set = document_.setDuration(duration); !set) message_.report(set.error().message, true);
  }
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  if (!document_.canUndo()) ImGui::BeginDisabled();
  if (ImGui::Button("Undo")) undo();
  if (!document_.canUndo()) ImGui::EndDisabled();
  ImGui::SameLine();
  if (!document_.canRedo()) ImGui::BeginDisabled();
  if (ImGui::Button("Redo")) redo();
  if (!document_.canRedo()) ImGui::EndDisabled();
}

// The second toolbar row: keying, the selected keys' interpolation, adding and removing tracks.
void TimelinePanel::drawKeyAndTrackControls(FaceDelegate& face) {
  // Keys.
  if (ImGui::Button("Key track")) keyTrack(face);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Key the selected track at the playhead with the value on screen");
  ImGui::SameLine();
  if (ImGui::Button("Key all")) keyAll(face);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80.0f);
  ImGui::Combo("new keys", &newKeyInterpolation_, kInterpolationNames, 4);
  ImGui::SameLine();
  const bool hasSelection = !document_.selection().empty();
  if (!hasSelection) ImGui::BeginDisabled();
  if (ImGui::Button("Delete")) deleteSelected();
  ImGui::SameLine();
  int selectedInterpolation = -1;
  if (hasSelection)
    if (const DocumentKey* k = document_.key(document_.selection().front())) selectedInterpolation = int(k->key.interpolation);
  ImGui::SetNextItemWidth(80.0f);
  if (ImGui::Combo("selected", &selectedInterpolation, kInterpolationNames, 4))
    (void)document_.setSelectedInterpolation(facial::KeyInterpolation(selectedInterpolation));
  if (!hasSelection) ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  // Tracks.
  const auto channels = pose_.channelNames();
  channelChoice_ = std::clamp(channelChoice_, 0, int(channels.size()) - 1);
  ImGui::SetNextItemWidth(190.0f);
  if (ImGui::BeginCombo("##channel", channels.empty() ? "" : channels[size_t(channelChoice_)].c_str())) {
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::InputTextWithHint("##filter", "filter", channelFilter_, sizeof channelFilter_);
    for (size_t c = 0; c < channels.size(); ++c) {
      if (!textCaseInsensitiveContains(channels[c], channelFilter_)) continue;
      const bool used = document_.findTrack(channels[c]).has_value();
      if (ImGui::Selectable(channels[c].c_str(), int(c) == channelChoice_, used ? ImGuiSelectableFlags_Disabled : 0))
        channelChoice_ = int(c);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (ImGui::Button("Add track") && !channels.empty()) {
    auto added = document_.addTrack(channels[size_t(channelChoice_)]);
    if (added) currentTrack_ = int(*added);
    else message_.report(added.error().message, true);
  }
  ImGui::SameLine();
  if (currentTrack_ < 0) ImGui::BeginDisabled();
  if (ImGui::Button("Remove track") && currentTrack_ >= 0) {
    (void)document_.removeTrack(size_t(currentTrack_));
    currentTrack_ = std::min(currentTrack_, int(document_.tracks().size()) - 1);
  }
  if (currentTrack_ < 0) ImGui::EndDisabled();
}

void TimelinePanel::drawTracks(FaceDelegate& face) {
  ImGui::BeginChild("tracks", {0.0f, 0.0f}, true);
  const auto tracks = document_.tracks();
  if (currentTrack_ >= int(tracks.size())) currentTrack_ = int(tracks.size()) - 1;
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const TimelineView view = TimelineView::fit(
      {.left = origin.x, .top = origin.y, .width = avail.x, .height = avail.y, .nameColumn = kNameColumn, .rulerHeight = kRulerHeight},
      document_);
  drawTrackNames(view, origin.x);
  // The key canvas: one invisible button takes every click on ruler and rows.
  ImGui::SetCursorScreenPos({view.canvasLeft(), view.top()});
  ImGui::InvisibleButton("canvas", {view.canvasWidth(), view.canvasHeight()});
  handleCanvasMouse(view, face);
  drawCanvas(view);
  ImGui::EndChild();
}

void TimelinePanel::drawTrackNames(const TimelineView& view, float left) {
  const auto tracks = document_.tracks();
  for (size_t t = 0; t < tracks.size(); ++t) {
    ImGui::SetCursorScreenPos({left, view.rowTop(t) + (view.rowHeight() - ImGui::GetTextLineHeight()) * 0.5f});
    ImGui::PushID(int(t));
    const bool known = pose_.knowsChannel(tracks[t].channel);
    if (!known) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.6f, 0.4f, 1.0f));
    if (ImGui::Selectable(tracks[t].channel.c_str(), currentTrack_ == int(t), 0, {kNameColumn - 8.0f, 0.0f})) {
      currentTrack_ = int(t);
      if (ImGui::GetIO().KeyCtrl) document_.selectTrack(t);
    }
    if (!known) {
      ImGui::PopStyleColor();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("this face has no channel '%s'", tracks[t].channel.c_str());
    }
    ImGui::PopID();
  }
}

// The canvas button's clicks and drags: a click on a key selects it (Ctrl or
// Shift: adds it) and starts dragging the selection; anywhere else it clears
// the selection (unless Ctrl) and scrubs the playhead.
void TimelinePanel::handleCanvasMouse(const TimelineView& view, FaceDelegate& face) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 mouse = io.MousePos;
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    const auto hit = view.hitAt(document_.tracks(), {mouse.x, mouse.y});
    if (hit) currentTrack_ = int(hit->row);
    if (hit && hit->key) {
      const KeyId key = *hit->key;
      if (io.KeyCtrl || io.KeyShift)
        document_.select(key, true);
      else if (!document_.isSelected(key))
        document_.select(key);
      if (document_.isSelected(key)) {
        document_.beginMove();
        draggingKeys_ = true;
        dragStartX_ = mouse.x;
        dragStartY_ = mouse.y;
      }
    } else {
      if (!io.KeyCtrl) document_.clearSelection();
      scrubbing_ = true;
    }
  }
  if (ImGui::IsItemActive()) {
    if (draggingKeys_) {
      document_.moveSelected(view.secondsFor(mouse.x - dragStartX_), view.valueFor(mouse.y - dragStartY_));
      face.takeControl(FaceSource::Timeline);
    } else if (scrubbing_) {
      seek(view.timeAt(mouse.x), face);
    }
  } else {
    if (draggingKeys_) document_.endMove();
    draggingKeys_ = false;
    scrubbing_ = false;
  }
}

void TimelinePanel::drawCanvas(const TimelineView& view) {
  const auto tracks = document_.tracks();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float left = view.canvasLeft(), right = view.canvasRight(), top = view.top(), rowsTop = view.rowsTop();
  // Ruler: five ticks per label, labels every rulerLabelStep() seconds.
  draw->AddRectFilled({left, top}, {right, rowsTop}, IM_COL32(40, 44, 54, 255));
  const float tickStep = TimelineView::rulerLabelStep(document_.duration()) / 5.0f;
  for (int i = 0; float(i) * tickStep <= document_.duration() + 1e-4f; ++i) {
    const float t = float(i) * tickStep, x = view.xAt(t);
    const bool major = i % 5 == 0;
    draw->AddLine({x, rowsTop - (major ? 10.0f : 5.0f)}, {x, rowsTop}, IM_COL32(150, 150, 160, 255));
    if (major) {
      char label[16];
      std::snprintf(label, sizeof label, "%.1f", double(t));
      // Right of its tick, except where that would run past the canvas (the clip's end).
      const float width = ImGui::CalcTextSize(label).x;
      const float labelX = x + 2.0f + width > right ? x - 2.0f - width : x + 2.0f;
      draw->AddText({labelX, top + 1.0f}, IM_COL32(190, 190, 200, 255), label);
      draw->AddLine({x, rowsTop}, {x, view.rowsBottom()}, IM_COL32(55, 60, 72, 255));
    }
  }
  // Rows: background, the curve, the keys.
  for (size_t t = 0; t < tracks.size(); ++t) {
    const float rowTop = view.rowTop(t);
    draw->AddRectFilled({left, rowTop}, {right, rowTop + view.rowHeight() - 1.0f},
                        int(t) == currentTrack_ ? IM_COL32(44, 52, 70, 255) : (t % 2 ? IM_COL32(32, 35, 42, 255) : IM_COL32(36, 39, 47, 255)));
    if (tracks[t].keys.empty()) continue;
    ImVec2 previous{left, view.yAt(t, document_.sample(t, 0.0f))};
    for (float x = left + 3.0f; x <= right; x += 3.0f) {
      const ImVec2 p{x, view.yAt(t, document_.sample(t, view.timeAt(x)))};
      draw->AddLine(previous, p, IM_COL32(110, 170, 230, 200), 1.5f);
      previous = p;
    }
    for (const DocumentKey& k : tracks[t].keys) {
      const ImVec2 c{view.xAt(k.key.time), view.yAt(t, k.key.value)};
      const float r = 5.0f;
      const ImU32 colour = document_.isSelected(k.id) ? IM_COL32(255, 180, 60, 255) : IM_COL32(225, 225, 235, 255);
      if (k.key.interpolation == facial::KeyInterpolation::Step)
        draw->AddRectFilled({c.x - r + 1, c.y - r + 1}, {c.x + r - 1, c.y + r - 1}, colour);
      else if (k.key.interpolation == facial::KeyInterpolation::Linear)
        draw->AddQuadFilled({c.x, c.y - r}, {c.x + r, c.y}, {c.x, c.y + r}, {c.x - r, c.y}, colour);
      else
        draw->AddCircleFilled(c, r - 0.5f, colour, 12);
    }
  }
  // Playhead.
  const float px = view.xAt(playhead_);
  draw->AddLine({px, top}, {px, view.rowsBottom()}, IM_COL32(255, 80, 80, 255), 2.0f);
  draw->AddTriangleFilled({px - 6, top}, {px + 6, top}, {px, top + 8}, IM_COL32(255, 80, 80, 255));
  if (tracks.empty()) {
    draw->AddText({left + 10.0f, rowsTop + 8.0f}, IM_COL32(160, 160, 170, 255),
                  "No tracks: pick a channel above and press 'Add track', or open a timeline file.");
  }
}

void TimelinePanel::draw(FaceDelegate& face) {
  drawToolbar(face);
  char status[160];
  std::snprintf(status, sizeof status, "%s%s  %zu tracks  %zu selected  %s", document_.name().c_str(),
                document_.dirty() ? " (modified)" : "", document_.tracks().size(), document_.selection().size(),
                face.source() == FaceSource::Timeline ? "drives the face" : "");
  ImGui::TextDisabled("%s", status);
  if (!message_.text.empty()) {
    ImGui::SameLine();
    message_.draw();
  }
  drawTracks(face);
  refreshPose();
}

}  // namespace editor
