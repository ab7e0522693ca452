#pragma once
// Autosave of the timeline being edited, so that a crash, a kill or a power
// cut loses at most the last few seconds of work:
//
//   TimelineAutosave autosave(autosavePathFor(documentPath));
//   autosave.update(document, now);   // every frame: writes when there are new unsaved edits
//   autosave.discard();               // after a successful save (or a clean close)
//
// The autosave is a timeline file of its own beside the document,
// ".<file name>.autosave" (hidden, and never mistaken for the document), written
// through replaceFileAtomically like every save. The next editor that opens the
// document calls recoverAutosave(): when an autosave newer than the document is
// there, the edits come back as an unsaved document, with a message saying
// where they came from; saving then writes them to the document and removes
// the autosave.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "editor/project.h"
#include "editor/timeline_document.h"
#include "engine/core/result.h"

namespace editor {

// "<dir>/.<name>.autosave" for "<dir>/<name>".
std::filesystem::path autosavePathFor(const std::filesystem::path& document);

// When an autosave is due: there are unsaved edits whose revision is not
// written yet, and `interval` has passed since the last write (the first edit
// is written at once).
class AutosaveSchedule {
 public:
  using Clock = std::chrono::steady_clock;
  explicit AutosaveSchedule(std::chrono::milliseconds interval) : interval_(interval) {}
  bool due(bool dirty, uint64_t revision, Clock::time_point now) const;
  // Unsaved edits not written yet, whatever the interval (a flush).
  bool pending(bool dirty, uint64_t revision) const { return dirty && revision != writtenRevision_; }
  void written(uint64_t revision, Clock::time_point now);
  void reset();

 private:
  std::chrono::milliseconds interval_;
  std::optional<Clock::time_point> lastWrite_;
  uint64_t writtenRevision_ = UINT64_MAX;
};

class TimelineAutosave {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kDefaultInterval{3000};

  explicit TimelineAutosave(std::filesystem::path file, std::chrono::milliseconds interval = kDefaultInterval);

  const std::filesystem::path& file() const { return file_; }
  // Writes the document's clip when it has unsaved edits the autosave does not
  // hold yet and `interval` has passed since the last write (the first edit is
  // written at once). true when it wrote; an error names the autosave file.
  eng::Result<bool> update(const TimelineDocument& document, Clock::time_point now);
  // Writes now whatever the interval (unsaved edits only).
  eng::Result<bool> flush(const TimelineDocument& document);
  // Removes the autosave file (the document is saved, or closed on purpose).
  void discard();

 private:
  eng::Result<bool> write(const TimelineDocument& document, Clock::time_point now);

  std::filesystem::path file_;
  AutosaveSchedule schedule_;
};

struct RecoveredTimeline {
  TimelineDocument document;  // unsaved (dirty): saving writes it to the document's path
  std::string message;        // one line: what was recovered from where
};

// The edits an earlier editor autosaved for `document` and never saved: the
// autosave when it exists and is newer than the document (or the document is
// gone). nullopt when there is nothing to recover (an autosave older than the
// document is stale and removed). An autosave that does not load is an error
// naming it; it is left in place for the user to look at.
eng::Result<std::optional<RecoveredTimeline>> recoverAutosave(const std::filesystem::path& document);

// The project's autosave covers what the project file holds: the project file
// as it would be saved (projectAutosavePath) and, when something is baked, the
// sculpted model (projectSculptAutosavePath). The clips are timeline files
// with their own autosave (TimelineAutosave beside each), which opening them
// recovers.
std::filesystem::path projectAutosavePath(const std::filesystem::path& project);
std::filesystem::path projectSculptAutosavePath(const std::filesystem::path& project);
// A graph edited in the diagram and not saved yet: ".<stem>.graph.autosave.json".
std::filesystem::path projectGraphAutosavePath(const std::filesystem::path& project);

struct RecoveredProject {
  Project project;      // unsaved: saving writes it to the project's path
  std::string message;  // one line: what was recovered from where
};

// The project as an earlier editor autosaved it and never saved: the autosave
// when it is newer than the project file (or that is gone); nullopt when there
// is nothing to recover (a stale autosave is removed). A broken autosave is an
// error naming it, left in place.
eng::Result<std::optional<RecoveredProject>> recoverProjectAutosave(const std::filesystem::path& project);
// Removes the project's autosave files (after a save, or a close on purpose).
void discardProjectAutosave(const std::filesystem::path& project);

}  // namespace editor
