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

TimelineAutosave::TimelineAutosave(fs::path file, std::chrono::milliseconds interval)
    : file_(std::move(file)), interval_(interval) {}

eng::Result<bool> TimelineAutosave::update(const TimelineDocument& document, Clock::time_point now) {
  if (!document.dirty() || document.revision() == writtenRevision_) return false;
  if (lastWrite_ && now - *lastWrite_ < interval_) return false;
  lastWrite_ = now;
  return write(document);
}

eng::Result<bool> TimelineAutosave::flush(const TimelineDocument& document) {
  if (!document.dirty() || document.revision() == writtenRevision_) return false;
  lastWrite_ = Clock::now();
  return write(document);
}

eng::Result<bool> TimelineAutosave::write(const TimelineDocument& document) {
  // Tracks without keys are left out (toTimeline): the clip as it would play.
  const facial::Timeline timeline = document.toTimeline();
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed(file_.string() + ": not autosaved: ");
  auto written = replaceFileAtomically(file_, [&](const fs::path& temp) -> eng::Result<void> {
    std::ofstream out(temp, std::ios::binary);
    if (!out) return eng::makeError(eng::ErrorKind::Io, file_.string() + ": cannot write the autosave (" + temp.string() + ")");
    out << facial::timelineToJson(timeline).dump(1) << '\n';
    out.close();
    if (!out) return eng::makeError(eng::ErrorKind::Io, file_.string() + ": autosave write failed (disk full?)");
    return {};
  });
  if (!written) return written.error();
  writtenRevision_ = document.revision();
  return true;
}

void TimelineAutosave::discard() {
  std::error_code ignored;
  fs::remove(file_, ignored);
  writtenRevision_ = UINT64_MAX;
  lastWrite_.reset();
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

}  // namespace

eng::Result<std::optional<RecoveredTimeline>> recoverAutosave(const fs::path& document) {
  const fs::path file = autosavePathFor(document);
  std::error_code error;
  const auto autosaved = fs::last_write_time(file, error);
  if (error) return std::optional<RecoveredTimeline>();  // no autosave
  const auto saved = fs::last_write_time(document, error);
  const bool documentExists = !error;
  if (documentExists && saved >= autosaved) {
    fs::remove(file, error);  // stale: the document was saved after it
    return std::optional<RecoveredTimeline>();
  }
  auto loaded = TimelineDocument::load(file);
  if (!loaded) return loaded.error().prefixed("cannot recover the autosaved edits: ");
  loaded->markUnsaved();
  std::string message = "recovered unsaved edits of " + document.string() + " from " + file.string() +
                        " (autosaved " + clockTime(autosaved) + (documentExists ? ", after the file was last saved" : "") +
                        "); save to keep them";
  return std::optional<RecoveredTimeline>(RecoveredTimeline{std::move(loaded).value(), std::move(message)});
}

}  // namespace editor
