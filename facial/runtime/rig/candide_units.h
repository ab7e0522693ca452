#pragma once
// The 14 animation units of the CANDIDE-3 mask (Ahlberg 2001), the FACS unit
// each realises, and how the rig's channels drive it. Shared by the importer
// (facial_bake, which names the morph targets "AU<n> <unit name>") and the
// Candide3 rig-mapping scheme.
#include <span>
#include <string>
#include <string_view>

namespace facial {

struct CandideChannelGain {
  std::string_view channel;  // actionUnits() channel name
  float gain;                // signed: CANDIDE parameters run both ways
};

struct CandideAnimationUnit {
  std::string_view name;  // as in candide3.wfm, e.g. "Nose wrinkler"
  int facsNumber;         // the FACS unit it realises, e.g. 9
  std::span<const CandideChannelGain> drive;  // empty: no channel of ours (jaw thrust / sideways)
};

std::span<const CandideAnimationUnit> candideAnimationUnits();
// The morph target name the importer gives a unit: "AU9 Nose wrinkler".
std::string candideTargetName(const CandideAnimationUnit& unit);
// By the file's unit name or the target name, case-insensitive; nullptr if unknown.
const CandideAnimationUnit* findCandideUnit(std::string_view name);

}  // namespace facial
