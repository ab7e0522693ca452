#include "editor/autosave.h"

#include <ctime>
#include <fstream>
#include <system_error>

#include "editor/atomic_file.h"
#include "facial/runtime/graph/timeline_json.h"

namespace editor {

namespace fs = std::filesystem;

fs::path autosavePathFor(const fs::path& document) {
  fs::path file = document;
  file.replace_filename("." + document.filename().string() + ".autosave");
  return file;
}

bool AutosaveSchedule::due(bool dirty, uint64_t revision, Clock::time_point now) const {
  return pending(dirty, revision) && !(lastWrite_ && now - *lastWrite_ < interval_);
}

void AutosaveSchedule::written(uint64_t revision, Clock::time_point now) {
  writtenRevision_ = revision;
  lastWrite_ = now;
}

void AutosaveSchedule::reset() {
  writtenRevision_ = UINT64_MAX;
  lastWrite_.reset();
}

TimelineAutosave::TimelineAutosave(fs::path file, std::chrono::milliseconds interval)
    : file_(std::move(file)), schedule_(interval) {}

eng::Result<bool> TimelineAutosave::update(const TimelineDocument& document, Clock::time_point now) {
  if (!schedule_.due(document.dirty(), document.revision(), now)) return false;
  schedule_.written(UINT64_MAX, now);  // a failed write waits for the interval too
  return write(document, now);
}

eng::Result<bool> TimelineAutosave::flush(const TimelineDocument& document) {
  if (!schedule_.pending(document.dirty(), document.revision())) return false;
  return write(document, Clock::now());
}

eng::Result<bool> TimelineAutosave::write(const TimelineDocument& document, Clock::time_point now) {
  // Tracks without keys are left out (toTimeline): the clip as it would play.
  const facial::Timeline timeline = document.toTimeline();
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed(file_.string() + ": not autosaved: ");
  auto written = writeJsonAtomically(facial::timelineToJson(timeline), file_);
  if (!written) return written.error();
  schedule_.written(document.revision(), now);
  return true;
}

void TimelineAutosave::discard() {
  std::error_code ignored;
  fs::remove(file_, ignored);
  schedule_.reset();
}

namespace {

std::string clockTime(fs::file_time_type written) {
  const auto system = std::chrono::file_clock::to_sys(written);
  const std::time_t t = std::chrono::system_clock::to_time_t(system);
  std::tm local{};
  localtime_r(&t, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &local);
  return text;
}

// When `autosave` holds edits newer than `document` (or the document is
// gone): its write time. A stale autosave is removed.
std::optional<fs::file_time_type> freshAutosave(const fs::path& autosave, const fs::path& document, bool& documentExists) {
  std::error_code error;
  const auto autosaved = fs::last_write_time(autosave, error);
  if (error) return std::nullopt;  // no autosave
  const auto saved = fs::last_write_time(document, error);
  documentExists = !error;
  if (documentExists && saved >= autosaved) {
    fs::remove(autosave, error);  // stale: the document was saved after it
    return std::nullopt;
  }
  return autosaved;
}

std::string recoveredMessage(const fs::path& document, const fs::path& autosave, fs::file_time_type autosaved, bool documentExists) {
  return "recovered unsaved edits of " + document.string() + " from " + autosave.string() + " (autosaved " +
         clockTime(autosaved) + (documentExists ? ", after the file was last saved" : "") + "); save to keep them";
}

}  // namespace

eng::Result<std::optional<RecoveredTimeline>> recoverAutosave(const fs::path& document) {
  const fs::path file = autosavePathFor(document);
  bool documentExists = false;
  const auto autosaved = freshAutosave(file, document, documentExists);
  if (!autosaved) return std::optional<RecoveredTimeline>();
  auto loaded = TimelineDocument::load(file);
  if (!loaded) return loaded.error().prefixed("cannot recover the autosaved edits: ");
  loaded->markUnsaved();
  return std::optional<RecoveredTimeline>(
      RecoveredTimeline{std::move(loaded).value(), recoveredMessage(document, file, *autosaved, documentExists)});
}

fs::path projectAutosavePath(const fs::path& project) { return autosavePathFor(project); }

fs::path projectSculptAutosavePath(const fs::path& project) {
  fs::path stem = project.filename();
  stem.replace_extension();
  return project.parent_path() / ("." + stem.string() + ".sculpt.autosave.glb");
}

fs::path projectGraphAutosavePath(const fs::path& project) {
  fs::path stem = project.filename();
  stem.replace_extension();
  return project.parent_path() / ("." + stem.string() + ".graph.autosave.json");
}

eng::Result<std::optional<RecoveredProject>> recoverProjectAutosave(const fs::path& project) {
  const fs::path file = projectAutosavePath(project);
  bool projectExists = false;
  const auto autosaved = freshAutosave(file, project, projectExists);
  if (!autosaved) return std::optional<RecoveredProject>();
  auto json = facial::readJsonFile(file);
  if (!json) return json.error().prefixed("cannot recover the autosaved project: ");
  // Beside the project: its relative paths read as the project's own.
  auto loaded = projectFromJson(*json, project);
  if (!loaded) return loaded.error().prefixed("cannot recover the autosaved project: " + file.string() + ": ");
  return std::optional<RecoveredProject>(
      RecoveredProject{std::move(loaded).value(), recoveredMessage(project, file, *autosaved, projectExists)});
}

void discardProjectAutosave(const fs::path& project) {
  std::error_code ignored;
  fs::remove(projectAutosavePath(project), ignored);
  fs::remove(projectSculptAutosavePath(project), ignored);
  fs::remove(projectGraphAutosavePath(project), ignored);
}

}  // namespace editor
