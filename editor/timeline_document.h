#pragma once
// The timeline editor's model: a keyframe clip being edited (tracks of keys
// over the rig's channels), the key selection, and every edit as an undoable
// command. Plain C++ with no UI, so the panel is a thin view over it and the
// editing rules are unit-tested on their own.
//
// Keys carry stable ids (selection survives re-sorting); every track stays
// sorted by time after every edit. A move is rigid: the whole selection
// shifts by one time delta, clamped so no selected key leaves [0, duration];
// a moved key landing on an unselected key of its track replaces it (as in
// Blender's "overwrite" on transform end). Drags are one undo step:
//
//   doc.beginMove();
//   doc.moveSelected(dt, dv);   // each frame, relative to beginMove()
//   doc.endMove();              // commits one "move keys" step (none if nothing moved)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/timeline.h"

namespace editor {

using KeyId = uint32_t;

struct DocumentKey {
  KeyId id = 0;
  // key.tangent says where its slopes come from; facial::resolveTangents()
  // re-derives them after every edit, as the runtime does when it reads the file.
  facial::Keyframe key;
};

struct DocumentTrack {
  std::string channel;
  std::vector<DocumentKey> keys;  // sorted by time, at least kMinKeySpacing apart
  // Preview only (what the editor plays): saved files hold every track.
  bool muted = false;
  bool solo = false;
};

// How a selection gesture combines with the keys already selected:
// a plain click / box replaces, Shift extends, Ctrl toggles.
enum class SelectMode { Replace, Extend, Toggle };

// Copied keys: their channels and times relative to the earliest one.
struct KeyClipboard {
  struct Entry {
    std::string channel;
    facial::Keyframe key;  // time relative to the first copied key
  };
  std::vector<Entry> keys;
  float span = 0.0f;  // last minus first copied time
  bool empty() const { return keys.empty(); }
};

// Editor playback: an optional loop range inside the clip and a speed.
struct PlaybackSettings {
  bool hasLoopRange = false;
  float loopStart = 0.0f, loopEnd = 0.0f;
  float speed = 1.0f;
  bool operator==(const PlaybackSettings&) const = default;
};

// The editor settings of a clip that its timeline file (what the runtime
// plays) does not hold; a project keeps them beside the clip.
struct TimelineSettings {
  float frameRate = 30.0f;
  PlaybackSettings playback;
  std::vector<std::string> muted, solo;  // channels
  bool operator==(const TimelineSettings&) const = default;
};

struct KeyLocation {
  size_t track = 0;
  size_t index = 0;  // in the track's sorted keys
};

class TimelineDocument {
 public:
  static constexpr float kMinKeySpacing = 1e-3f;  // seconds; closer keys are one key
  static constexpr float kMinDuration = 0.01f;

  explicit TimelineDocument(std::string name = "untitled", float duration = 2.0f);
  // Fails when the timeline does not validate (the message says why).
  static eng::Result<TimelineDocument> fromTimeline(const facial::Timeline& timeline);
  // A timeline file (timeline_json.h); errors name the file.
  static eng::Result<TimelineDocument> load(const std::filesystem::path& path);

  // The clip as the runtime plays it. Tracks without keys are left out.
  facial::Timeline toTimeline() const;
  // Writes the timeline file through a temporary sibling, so a failed save
  // never damages an existing file. Fails (nothing written) when a track has
  // no keys. Marks the document saved.
  eng::Result<void> save(const std::filesystem::path& path);

  const std::string& name() const { return state_.name; }
  float duration() const { return state_.duration; }
  facial::LoopMode loop() const { return state_.loop; }
  std::span<const DocumentTrack> tracks() const { return state_.tracks; }
  std::optional<size_t> findTrack(std::string_view channel) const;
  std::optional<KeyLocation> locate(KeyId id) const;
  const DocumentKey* key(KeyId id) const;
  // The track's value at `time` (0 for a track without keys).
  float sample(size_t track, float time) const;
  // Values are clamped to this range on every edit ([0, 1]: channel weights).
  float minValue() const { return minValue_; }
  float maxValue() const { return maxValue_; }
  void setValueRange(float minValue, float maxValue);

  // Selection (not part of undo history).
  std::span<const KeyId> selection() const { return selection_; }
  bool isSelected(KeyId id) const;
  // additive: toggles `id` in the selection; otherwise selects only it. Unknown ids are ignored.
  void select(KeyId id, bool additive = false);
  void selectTrack(size_t track);
  void clearSelection() { selection_.clear(); }
  void selectKeys(std::span<const KeyId> ids, SelectMode mode);
  // Keys with time in [t0, t1] and value in [v0, v1] on `tracks` (every track when empty).
  std::vector<KeyId> keysInBox(float t0, float t1, std::span<const size_t> tracks, float v0 = -INFINITY,
                               float v1 = INFINITY) const;
  void selectBox(float t0, float t1, std::span<const size_t> tracks, SelectMode mode) {
    selectKeys(keysInBox(t0, t1, tracks), mode);
  }
  // Every key within half a frame of `time`, on every track (a column of the dope sheet).
  void selectAtTime(float time, SelectMode mode);
  void selectAll();

  // The frame rate of nudges and snapping (frames per second).
  float frameRate() const { return state_.frameRate; }
  float frameDuration() const { return 1.0f / state_.frameRate; }
  // `time` on the nearest frame.
  float snapTime(float time) const;
  const PlaybackSettings& playback() const { return state_.playback; }
  // The playhead after `playTime` seconds of playback (speed applied by the
  // caller's clock): wraps inside the loop range once it is reached, else
  // follows the clip's loop mode as the runtime does.
  float playheadAt(float playTime) const;
  TimelineSettings settings() const;
  // Puts saved settings back (a project opened): not an edit, the document
  // stays as clean as it was; channels without a track and values out of range are skipped.
  void restoreSettings(const TimelineSettings& settings);
  // Whether a track is heard in the preview: not muted, and soloed when any track is.
  bool audible(size_t track) const;

  // Edits: each successful one is one undo step; a failed one changes nothing
  // and says why.
  eng::Result<size_t> addTrack(std::string channel);
  eng::Result<void> removeTrack(size_t track);
  // A key at `time` (clamped into [0, duration]); an existing key closer than
  // kMinKeySpacing gets the new value and interpolation instead. Selects it.
  eng::Result<KeyId> setKey(size_t track, float time, float value,
                            facial::KeyInterpolation interpolation = facial::KeyInterpolation::Linear);
  eng::Result<void> deleteSelected();
  // Cubic (Hermite) turns auto tangents on for those keys.
  eng::Result<void> setSelectedInterpolation(facial::KeyInterpolation interpolation);
  // Fails below kMinDuration, when not finite, or when keys lie beyond the new end.
  eng::Result<void> setDuration(float duration);
  eng::Result<void> setLoop(facial::LoopMode loop);
  // The curve view's key shape: interpolation of the segment it starts and
  // where its tangents come from; in / out are used by Smooth (out) and Broken.
  eng::Result<void> setKeyShape(KeyId id, facial::KeyInterpolation interpolation, facial::TangentMode tangent,
                                std::optional<float> inSlope = {}, std::optional<float> outSlope = {});
  // Keys `channel` at 1 and every other track of `group` at 0 at `time` (one
  // step; the track is made when missing, holding 0 at the group's earlier key
  // times; the clip grows to `time`): an emotion keyed over the others, "neutral -> happy -> surprise".
  // The keys get `interpolation` / `tangent` and become the selection.
  eng::Result<void> keyExclusive(const std::string& channel, std::span<const std::string_view> group, float time,
                                 facial::KeyInterpolation interpolation, facial::TangentMode tangent);
  // Copy / paste / duplicate: pasted keys land at `time` + their copied offsets
  // on the tracks of their channels (made when missing), the clip growing to
  // hold them; they become the selection.
  KeyClipboard copySelection() const;
  eng::Result<void> paste(const KeyClipboard& clipboard, float time);
  // A copy of the selection one frame after its last key.
  eng::Result<void> duplicateSelected();
  // The selection by whole frames (arrow keys); clamped at the clip's ends.
  eng::Result<void> nudgeSelected(int frames);
  // Sets the frame rate and moves the selected keys (all keys when none are
  // selected) to their nearest frames.
  eng::Result<void> snapToFrames(float framesPerSecond);
  eng::Result<void> setMuted(size_t track, bool muted);
  eng::Result<void> setSolo(size_t track, bool solo);
  // A loop range inside [0, duration] (at least a frame long), or none.
  eng::Result<void> setLoopRange(float start, float end);
  eng::Result<void> clearLoopRange();
  // Playback speed, 0.05 to 20 (negative plays backwards is not offered).
  eng::Result<void> setSpeed(float speed);

  // Several edits as one undo step `label` (a recording's keys): all of them
  // stay, or none when one fails (its error is returned).
  template <typename Edits>
  eng::Result<void> grouped(std::string label, Edits&& edits);

  // Drag of the selection (see the file comment).
  void beginMove();
  // dt, dv relative to beginMove(); false when not moving or not finite.
  bool moveSelected(float dt, float dv);
  void endMove();
  void cancelMove();
  bool moving() const { return moveStart_.has_value(); }
  // One-shot move: beginMove + moveSelected + endMove.
  eng::Result<void> moveSelectedBy(float dt, float dv);
  // A tangent handle's drag (inside beginMove / endMove): the key's slopes
  // set, a Smooth key keeping both sides one slope, an Auto or Flat one
  // becoming Smooth (Broken with `breakTangent`: Alt in the curve view).
  bool dragTangent(KeyId id, float inSlope, float outSlope, bool breakTangent);

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  // What undo / redo would revert ("" when nothing).
  std::string_view undoLabel() const { return undo_.empty() ? std::string_view() : undo_.back().label; }
  std::string_view redoLabel() const { return redo_.empty() ? std::string_view() : redo_.back().label; }
  bool undo();
  bool redo();

  // Unsaved changes since load / the last save (undoing back to it is clean again).
  bool dirty() const { return state_.serial != savedSerial_; }
  // Marks the content as not saved to its file (edits recovered from an autosave).
  void markUnsaved() { savedSerial_ = 0; ++revision_; }
  // Changes with every edit, undo and redo (players re-sample on change).
  uint64_t revision() const { return revision_; }

 private:
  struct State {
    std::string name;
    float duration = 2.0f;
    facial::LoopMode loop = facial::LoopMode::Loop;
    std::vector<DocumentTrack> tracks;
    float frameRate = 30.0f;
    PlaybackSettings playback;
    uint64_t serial = 0;  // identifies this exact content (dirty tracking)
  };
  struct UndoStep {
    std::string label;
    State before;
  };

  void commit(std::string label, State before);
  void normaliseTrack(DocumentTrack& track) const;
  void dropStaleSelection();
  // Shared by the one-step edits: a copy of the state before `edit`, committed as `label` when edit succeeds.
  template <typename Edit>
  eng::Result<void> edit(std::string label, Edit&& edit);
  eng::Result<void> requireSelection(std::string_view action) const;

  State state_;
  std::vector<KeyId> selection_;
  std::vector<UndoStep> undo_;
  std::vector<UndoStep> redo_;
  std::optional<State> moveStart_;
  KeyId nextId_ = 1;
  uint64_t nextSerial_ = 1;
  uint64_t savedSerial_ = 0;
  uint64_t revision_ = 0;
  float minValue_ = 0.0f;
  float maxValue_ = 1.0f;
};

template <typename Edits>
eng::Result<void> TimelineDocument::grouped(std::string label, Edits&& edits) {
  const size_t mark = undo_.size();
  State before = state_;
  eng::Result<void> done = edits();
  const bool changed = undo_.size() > mark;
  undo_.erase(undo_.begin() + std::ptrdiff_t(std::min(mark, undo_.size())), undo_.end());
  if (!done) {
    state_ = std::move(before);
    ++revision_;
    dropStaleSelection();
    return done;
  }
  if (changed) commit(std::move(label), std::move(before));
  return {};
}

}  // namespace editor
