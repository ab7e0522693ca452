// The editor's timeline documents (editor/timeline_document.h): a file the
// editor opens must save (through editor/atomic_file) and open again to the
// same clip, and survive a round of edits, undo and redo.
#include <string>

#include "editor/timeline_document.h"
#include "fuzz/fuzz_support.h"

namespace {

bool sameClip(const facial::Timeline& a, const facial::Timeline& b) {
  if (a.name != b.name || a.duration != b.duration || a.loop != b.loop || a.tracks.size() != b.tracks.size())
    return false;
  for (size_t t = 0; t < a.tracks.size(); ++t) {
    if (a.tracks[t].channel != b.tracks[t].channel) return false;
    const auto ka = a.trackKeys(t), kb = b.trackKeys(t);
    if (ka.size() != kb.size()) return false;
    for (size_t k = 0; k < ka.size(); ++k)
      if (ka[k].time != kb[k].time || ka[k].value != kb[k].value || ka[k].interpolation != kb[k].interpolation)
        return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = fuzz::writeInput("clip.json", data, size);
  auto document = editor::TimelineDocument::load(path);
  if (!document) return 0;
  const facial::Timeline before = document->toTimeline();
  const auto saved = document->save(fuzz::scratchDir() / "saved.json");
  if (!saved) return 0;  // e.g. a track without keys: refused, nothing written
  auto reopened = editor::TimelineDocument::load(fuzz::scratchDir() / "saved.json");
  FUZZ_PROPERTY(reopened.ok(), "a saved document does not open: " + reopened.error().message);
  FUZZ_PROPERTY(sameClip(before, reopened->toTimeline()), "save + open changed the clip");

  // Edits on whatever was loaded: select everything, move, re-time, undo all.
  for (size_t t = 0; t < reopened->tracks().size(); ++t) reopened->selectTrack(t);
  (void)reopened->moveSelectedBy(0.1f, -0.2f);
  (void)reopened->setSelectedInterpolation(facial::KeyInterpolation::Hermite);
  (void)reopened->setDuration(reopened->duration() * 2.0f);
  if (!reopened->tracks().empty()) (void)reopened->setKey(0, 0.3f, 0.5f);
  while (reopened->undo()) {
  }
  FUZZ_PROPERTY(sameClip(before, reopened->toTimeline()), "undoing every edit did not restore the clip");
  while (reopened->redo()) {
  }
  return 0;
}
