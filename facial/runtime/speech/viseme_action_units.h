#pragma once
// Speech over action units: the lip and jaw units each viseme is made of (how
// a FACS-driven face speaks), and the mouth-ownership table (how an emotion's
// own mouth yields to speech while the brows, eyes, cheeks and head stay the
// emotion's). Used by rigs that speak through their action units
// (rig/speech_rig.cpp) and by everything that layers speech over an emotion
// (the speech node, facial::Character).
#include <cstdint>
#include <span>
#include <string_view>

#include "facial/runtime/speech/viseme.h"

namespace facial {

struct VisemeActionUnit {
  std::string_view channel;  // an actionUnits() channel name
  float weight;
  // What a face without `channel` moves instead (empty: nothing). The lip
  // pucker, funneler and suck, the mouth stretch and the tongue are recent
  // additions most FACS rigs (CANDIDE-3, older heads) lack: rounding then
  // falls back to the lip tightener and a wide jaw to the jaw drop.
  std::string_view fallback = {};
  float fallbackWeight = 0.0f;
};
// The units of one viseme (empty for sil: the relaxed, closed mouth).
std::span<const VisemeActionUnit> visemeActionUnits(Viseme viseme);

// While speech is active, the emotion's weight on a mouth channel is scaled by
//   1 - activity * (1 - kept) - activity * lipClosure * (kept - keptOnClosure)
// i.e. `kept` of it stays through speech and `keptOnClosure` while the lips
// close (p b m). Speech owns a channel whose kept is 0 (jaw drop, lips part,
// stretch, pressor, tightener, lower lip): the emotion's shape there fades as
// speech starts, so it never fights the visemes. Channels not in the table
// (brows, lids, cheek raiser, nose, blink) stay the emotion's.
struct MouthOwnership {
  std::string_view channel;
  float kept;           // fraction of the emotion's weight left at full speech activity
  float keptOnClosure;  // fraction left on a full bilabial closure (<= kept)
};
std::span<const MouthOwnership> mouthOwnershipTable();

// Applies the table to action-unit weights (actionUnits() order) in place;
// activity: how much speech owns the mouth (the track's kOwnershipChannel).
void yieldMouthToSpeech(std::span<float> auWeights, float activity, float lipClosure);

}  // namespace facial
