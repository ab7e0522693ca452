#pragma once
// The viseme set lip sync speaks in: the 15 Oculus (OVRLipSync) visemes that
// Ready Player Me avatars and most viseme rigs carry as viseme_<name> targets,
// plus the articulation channels a rig without visemes needs (jaw, lips).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace facial {

enum class Viseme : uint8_t { sil, PP, FF, TH, DD, kk, CH, SS, nn, RR, aa, E, I, O, U };
inline constexpr size_t kVisemeCount = 15;

// The names as the Oculus set writes them ("sil", "PP", ..., "U"); exact match.
std::string_view visemeName(Viseme viseme);
std::optional<Viseme> visemeFromName(std::string_view name);
// "sil, PP, FF, ... or U", for messages.
std::string visemeNameList();

// Derived channels, computed from the viseme weights: what a jaw bone or an
// ARKit-style rig (jawOpen, mouthClose, mouthPucker) follows.
enum class MouthChannel : uint8_t {
  JawOpen,      // 0 closed teeth .. 1 the open "aa"
  LipClosure,   // 1 lips together (bilabials, rest)
  LipRounding,  // 1 fully rounded / protruded lips ("oo")
};
inline constexpr size_t kMouthChannelCount = 3;
std::string_view mouthChannelName(MouthChannel channel);

// A track's channels: the 15 visemes, the 3 mouth channels, then how much
// speech owns the mouth (1 through a line and its short pauses, 0 at rest
// before and after it and in long pauses: the emotion's mouth then shows).
inline constexpr size_t kOwnershipChannel = kVisemeCount + kMouthChannelCount;
inline constexpr size_t kSpeechChannelCount = kOwnershipChannel + 1;

// How a viseme sets the mouth channels (a mouth shape in three numbers).
struct MouthShape {
  float jawOpen;
  float lipClosure;
  float lipRounding;
};
const MouthShape& mouthShapeOf(Viseme viseme);

inline bool isVowelViseme(Viseme v) { return v >= Viseme::aa; }
inline bool isRoundedViseme(Viseme v) { return v == Viseme::O || v == Viseme::U; }

}  // namespace facial
