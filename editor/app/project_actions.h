#pragma once
// The File menu's work: New, Open, Save, Save As, the recent projects, the
// autosave of the whole project and Export .glb, over the panels that hold
// the work (editor/project.h is the file; this puts it into the panels and
// takes it out of them). The face itself is loaded once per editor, so a
// project made on another model opens in a new editor (the app asks
// madeOnAnotherFace first; runEditor loads the project's face).
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "app/face_setup.h"
#include "app/sequence_recorder.h"
#include "editor/app/face_delegate.h"
#include "editor/app/sculpt_panel.h"
#include "editor/app/state_machine_panel.h"
#include "editor/app/timeline_panel.h"
#include "editor/autosave.h"
#include "editor/project.h"

namespace editor {

// What the app gives the project besides the panels: the view it shows.
class ProjectViewHost {
 public:
  virtual ~ProjectViewHost() = default;
  virtual ProjectView viewSettings() const = 0;
  virtual void applyViewSettings(const ProjectView& view) = 0;
};

struct ProjectPanels {
  const app::FaceSetup* face = nullptr;
  StateMachinePanel* machine = nullptr;
  TimelinePanel* timeline = nullptr;
  SculptPanel* sculpt = nullptr;
  ProjectViewHost* view = nullptr;
};

// Clip exports: square frames of this size, the GIF at 20 and the video at 30 frames a second.
inline constexpr uint32_t kClipExportSize = 384;
inline constexpr float kGifExportFps = 20.0f, kVideoExportFps = 30.0f;

class ProjectActions {
 public:
  // model / rigmap / graph: what the editor was started with ("" = defaults).
  ProjectActions(ProjectPanels panels, std::filesystem::path model, std::filesystem::path rigmap, std::filesystem::path graph,
                 RecentProjects recent = RecentProjects());

  // Each returns false after reporting why (the menu's message line and the log).
  bool newProject();
  bool open(const std::filesystem::path& path);
  // The project at `path` was made on another face or rig map than this
  // editor's: it opens in a new editor (runEditor), not in this one.
  bool madeOnAnotherFace(const std::filesystem::path& path) const;
  // Save to the project's file; an untitled project has none (Save As).
  bool save();
  bool saveAs(const std::filesystem::path& path);
  bool exportGlb(const std::filesystem::path& path);
  // The clip (empty: the one being edited; else a project clip by name) played
  // headless into an animated GIF, seen from the view on screen.
  bool exportGif(const std::filesystem::path& path, const std::string& clip);
  // The same frames as the GIF, at 30 fps, as an H.264 MP4 without sound (the
  // clip holds no speech): complete or absent (audio::VideoWriter).
  bool exportVideo(const std::filesystem::path& path, const std::string& clip);

  // Unsaved changes: the clip's edits or settings, bakes or their weights, another or an edited graph.
  bool dirty() const;
  // "NAME* - facial editor" ("untitled" before the first save; "*" when dirty).
  std::string windowTitle() const;
  // Every frame: writes the project's autosave when there are new unsaved changes (at most every 3 s).
  void update(std::chrono::steady_clock::time_point now);
  // The window is going away with unsaved changes the user chose to keep
  // (an error, not a Discard): autosave them now.
  void keepUnsaved();
  // Quit > Discard: the autosave is dropped with the changes.
  void discardUnsaved();

  const std::filesystem::path& path() const { return path_; }
  const RecentProjects& recent() const { return recent_; }
  const PanelMessage& message() const { return message_; }

 private:
  Project current(const std::filesystem::path& projectFile) const;
  // The clip an export plays: the one being edited (clip empty or its name) or a project clip, loaded into `other`.
  eng::Result<const TimelineDocument*> clipToExport(const std::string& clip, std::optional<TimelineDocument>& other) const;
  // The clip played headless as the window draws it (GIF and video export): `sequence` without its length, each frame to `sink`.
  eng::Result<app::SequenceSummary> recordClip(const TimelineDocument& clip, app::SequenceOptions sequence, const app::FrameSink& sink) const;
  bool apply(const Project& project, const std::filesystem::path& path);
  bool fail(const std::string& problem) {
    message_.report(problem, true);
    return false;
  }
  uint64_t revision() const;
  // The diagram changed the graph since it was loaded or saved.
  bool graphEdited() const;
  void rememberSaved();
  bool writeAutosave();
  bool reportAutosave(const std::string& problem);

  ProjectPanels panels_;
  std::filesystem::path model_, rigmap_, graph_;
  std::filesystem::path path_;  // empty: untitled
  std::vector<ProjectClip> otherClips_;  // the project's clips after the first (the panel edits one)
  bool recoveredUnsaved_ = false;        // opened from its autosave: unsaved until saved
  RecentProjects recent_;
  PanelMessage message_;
  // What was saved (or opened), for dirty(): the bakes and their weights, the graph.
  std::vector<std::pair<std::string, float>> savedBakes_;
  std::filesystem::path savedGraph_;
  AutosaveSchedule autosave_{std::chrono::milliseconds(3000)};
  std::vector<std::string> autosavedBakeNames_;  // what the autosave's sculpt .glb holds
  std::string autosaveError_;  // the last autosave failure reported (reported once)
};

}  // namespace editor
