#include "facial/runtime/rig/candide_units.h"

#include <array>

#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

// Gains: CANDIDE units span the full motion at parameter 1. The mask has no lip
// corner puller, but its lip corner depressor run backwards lifts the corners,
// so AU12 drives it negatively (half per side: the unit is bilateral). The
// mask's lip stretcher only pulls the corners sideways and back, which on its
// curved mouth reads as a grin; a lip stretcher (risorius, with the platysma)
// also draws the corners down, so AU20 adds half the depressor: the stretched
// mouth then reads tense, as in fear.
constexpr CandideChannelGain kNoseWrinkler[] = {{"AU9_NoseWrinkler", 1.0f}};
constexpr CandideChannelGain kJawDrop[] = {{"AU26_JawDrop", 0.7f}, {"AU25_LipsPart", 0.15f}};
constexpr CandideChannelGain kUpperLipRaiser[] = {{"AU10_UpperLipRaiser", 1.0f}};
constexpr CandideChannelGain kLipStretcher[] = {{"AU20_LipStretcher", 1.0f}};
constexpr CandideChannelGain kLipCornerDepressor[] = {{"AU15_LipCornerDepressor", 1.0f},
                                                      {"AU12_LipCornerPuller_L", -0.5f},
                                                      {"AU12_LipCornerPuller_R", -0.5f},
                                                      {"AU20_LipStretcher", 0.5f}};
constexpr CandideChannelGain kLipPresser[] = {{"AU24_LipPressor", 1.0f}, {"AU23_LipTightener", 0.5f}};
constexpr CandideChannelGain kOuterBrowRaiser[] = {{"AU2_OuterBrowRaiser_L", 0.5f}, {"AU2_OuterBrowRaiser_R", 0.5f}};
constexpr CandideChannelGain kInnerBrowsRaiser[] = {{"AU1_InnerBrowRaiser", 1.0f}};
constexpr CandideChannelGain kBrowLowerer[] = {{"AU4_BrowLowerer", 1.0f}};
constexpr CandideChannelGain kEyesClosed[] = {{"AU45_Blink_L", 0.5f}, {"AU45_Blink_R", 0.5f}};
constexpr CandideChannelGain kLidTightener[] = {{"AU7_LidTightener", 1.0f}, {"AU6_CheekRaiser", 0.3f}};
constexpr CandideChannelGain kUpperLidRaiser[] = {{"AU5_UpperLidRaiser", 1.0f}};

const std::array kUnits = {
    CandideAnimationUnit{"Nose wrinkler", 9, kNoseWrinkler},
    CandideAnimationUnit{"Jaw z-push", 29, {}},  // AU29 jaw thrust
    CandideAnimationUnit{"Jaw x-push", 30, {}},  // AU30 jaw sideways
    CandideAnimationUnit{"Jaw drop", 26, kJawDrop},
    CandideAnimationUnit{"Upper lip raiser", 10, kUpperLipRaiser},
    CandideAnimationUnit{"Lip stretcher", 20, kLipStretcher},
    CandideAnimationUnit{"Lip corner depressor", 15, kLipCornerDepressor},
    CandideAnimationUnit{"Lip presser", 24, kLipPresser},
    CandideAnimationUnit{"Outer brow raiser", 2, kOuterBrowRaiser},
    CandideAnimationUnit{"Inner brows raiser", 1, kInnerBrowsRaiser},
    CandideAnimationUnit{"Brow lowerer", 4, kBrowLowerer},
    CandideAnimationUnit{"Eyes closed", 45, kEyesClosed},
    CandideAnimationUnit{"Lid tightener", 7, kLidTightener},
    CandideAnimationUnit{"Upper lid raiser", 5, kUpperLidRaiser},
};

}  // namespace

std::span<const CandideAnimationUnit> candideAnimationUnits() { return kUnits; }

std::string candideTargetName(const CandideAnimationUnit& unit) {
  return "AU" + std::to_string(unit.facsNumber) + " " + std::string(unit.name);
}

const CandideAnimationUnit* findCandideUnit(std::string_view name) {
  const std::string lower = asciiLower(name);
  for (const CandideAnimationUnit& unit : kUnits)
    if (lower == asciiLower(unit.name) || lower == asciiLower(candideTargetName(unit))) return &unit;
  return nullptr;
}

}  // namespace facial
