#include "facial/runtime/speech/viseme_action_units.h"

#include <algorithm>
#include <array>

#include "facial/runtime/rig/action_units.h"

namespace facial {
namespace {

// Per viseme, after the mouth shapes of mouthShapeOf (jaw opening ~ AU26,
// AU25 for any parted lips) and the Oculus reference images. Rounded vowels
// protrude the lips: U mostly pucker (a small opening, little jaw), O mostly
// funnel (a wider round opening over an open jaw); CH/SH flare the lips in a
// funnel. The tongue tip shows between the teeth for TH and rises behind them
// for DD and nn (t d n l). FF is the lower lip pushed up (AU17) under a raised
// upper lip (AU10). A face without a unit uses its fallback (see the header).
using VAU = VisemeActionUnit;
constexpr std::string_view kTightener = "AU23_LipTightener";
constexpr VAU kPP[] = {{"AU24_LipPressor", 0.8f}, {"AU23_LipTightener", 0.3f}, {"AU28_LipSuck", 0.2f}};
constexpr VAU kFF[] = {{"AU10_UpperLipRaiser", 0.3f}, {"AU17_ChinRaiser", 0.4f}, {"AU25_LipsPart", 0.3f}, {"AU26_JawDrop", 0.1f}};
constexpr VAU kTH[] = {{"AU19_TongueShow", 1.0f}, {"AU25_LipsPart", 0.6f}, {"AU26_JawDrop", 0.15f}};
constexpr VAU kDD[] = {{"AU19_TongueShow", 0.5f}, {"AU25_LipsPart", 0.6f}, {"AU26_JawDrop", 0.2f}};
constexpr VAU kKK[] = {{"AU25_LipsPart", 0.6f}, {"AU26_JawDrop", 0.25f}};
constexpr VAU kCH[] = {{"AU22_LipFunneler", 0.6f, kTightener, 0.4f}, {"AU10_UpperLipRaiser", 0.2f}, {"AU25_LipsPart", 0.6f},
                       {"AU26_JawDrop", 0.15f}};
constexpr VAU kSS[] = {{"AU20_LipStretcher", 0.3f}, {"AU25_LipsPart", 0.7f}, {"AU26_JawDrop", 0.1f}};
constexpr VAU kNN[] = {{"AU19_TongueShow", 0.4f}, {"AU25_LipsPart", 0.5f}, {"AU26_JawDrop", 0.15f}};
constexpr VAU kRR[] = {{"AU18_LipPucker", 0.3f, kTightener, 0.4f}, {"AU25_LipsPart", 0.5f}, {"AU26_JawDrop", 0.2f}};
constexpr VAU kAA[] = {{"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 1.0f}, {"AU27_MouthStretch", 0.15f}};
constexpr VAU kE[] = {{"AU20_LipStretcher", 0.4f}, {"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 0.55f}};
constexpr VAU kI[] = {{"AU20_LipStretcher", 0.6f}, {"AU25_LipsPart", 0.8f}, {"AU26_JawDrop", 0.3f}};
constexpr VAU kO[] = {{"AU22_LipFunneler", 0.8f, kTightener, 0.6f}, {"AU18_LipPucker", 0.3f}, {"AU25_LipsPart", 1.0f},
                      {"AU26_JawDrop", 0.6f}};
constexpr VAU kU[] = {{"AU18_LipPucker", 0.9f, kTightener, 0.9f}, {"AU22_LipFunneler", 0.3f}, {"AU25_LipsPart", 0.6f},
                      {"AU26_JawDrop", 0.3f}};
const std::array<std::span<const VAU>, kVisemeCount> kVisemeUnits = {
    std::span<const VAU>{}, kPP, kFF, kTH, kDD, kKK, kCH, kSS, kNN, kRR, kAA, kE, kI, kO, kU};

// The mouth-ownership table (docs/speech.md, "Speaking with an emotion").
constexpr std::array<MouthOwnership, 18> kOwnership = {{
    {"AU12_LipCornerPuller_L", 0.75f, 0.55f},   // the smile stays, eased on p/b/m so the lips can meet
    {"AU12_LipCornerPuller_R", 0.75f, 0.55f},
    {"AU15_LipCornerDepressor", 0.85f, 0.7f},  // sad corners stay
    {"AU10_UpperLipRaiser", 0.5f, 0.2f},       // disgust's sneer, shared; it would part closed lips
    {"AU17_ChinRaiser", 0.5f, 0.5f},
    {"AU16_LowerLipDepressor", 0.0f, 0.0f},    // speech owns the opening, rounding and tongue shapes
    {"AU18_LipPucker", 0.0f, 0.0f},
    {"AU19_TongueShow", 0.0f, 0.0f},
    {"AU20_LipStretcher", 0.0f, 0.0f},
    {"AU22_LipFunneler", 0.0f, 0.0f},
    {"AU23_LipTightener", 0.0f, 0.0f},
    {"AU24_LipPressor", 0.0f, 0.0f},
    {"AU25_LipsPart", 0.0f, 0.0f},
    {"AU26_JawDrop", 0.0f, 0.0f},
    {"AU27_MouthStretch", 0.0f, 0.0f},
    {"AU28_LipSuck", 0.0f, 0.0f},
    {"AU29_JawThrust", 0.0f, 0.0f},
    {"AU9_NoseWrinkler", 1.0f, 1.0f},          // listed to say so: the nose stays the emotion's
}};

}  // namespace

std::span<const VisemeActionUnit> visemeActionUnits(Viseme viseme) { return kVisemeUnits[static_cast<size_t>(viseme)]; }

std::span<const MouthOwnership> mouthOwnershipTable() { return kOwnership; }

void yieldMouthToSpeech(std::span<float> auWeights, float activity, float lipClosure) {
  activity = std::clamp(activity, 0.0f, 1.0f);
  lipClosure = std::clamp(lipClosure, 0.0f, 1.0f);
  for (const MouthOwnership& row : kOwnership) {
    const std::optional<uint32_t> channel = actionUnitIndex(row.channel);
    if (!channel || *channel >= auWeights.size()) continue;
    const float scale = 1.0f - activity * (1.0f - row.kept) - activity * lipClosure * (row.kept - row.keptOnClosure);
    auWeights[*channel] *= std::max(scale, 0.0f);
  }
}

}  // namespace facial
