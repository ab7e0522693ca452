#include "facial/runtime/rig/action_units.h"

#include <array>

namespace facial {
namespace {

using R = FaceRegion;
using S = FaceSide;

constexpr std::array kActionUnits = {
    ActionUnitInfo{"AU1_InnerBrowRaiser", 1, "Inner Brow Raiser", R::Upper, S::Both},
    ActionUnitInfo{"AU2_OuterBrowRaiser_L", 2, "Outer Brow Raiser", R::Upper, S::Left},
    ActionUnitInfo{"AU2_OuterBrowRaiser_R", 2, "Outer Brow Raiser", R::Upper, S::Right},
    ActionUnitInfo{"AU4_BrowLowerer", 4, "Brow Lowerer", R::Upper, S::Both},
    ActionUnitInfo{"AU5_UpperLidRaiser", 5, "Upper Lid Raiser", R::Upper, S::Both},
    ActionUnitInfo{"AU6_CheekRaiser", 6, "Cheek Raiser", R::Upper, S::Both},
    ActionUnitInfo{"AU7_LidTightener", 7, "Lid Tightener", R::Upper, S::Both},
    ActionUnitInfo{"AU9_NoseWrinkler", 9, "Nose Wrinkler", R::Lower, S::Both},
    ActionUnitInfo{"AU10_UpperLipRaiser", 10, "Upper Lip Raiser", R::Lower, S::Both},
    ActionUnitInfo{"AU12_LipCornerPuller_L", 12, "Lip Corner Puller", R::Lower, S::Left},
    ActionUnitInfo{"AU12_LipCornerPuller_R", 12, "Lip Corner Puller", R::Lower, S::Right},
    ActionUnitInfo{"AU15_LipCornerDepressor", 15, "Lip Corner Depressor", R::Lower, S::Both},
    ActionUnitInfo{"AU16_LowerLipDepressor", 16, "Lower Lip Depressor", R::Lower, S::Both},
    ActionUnitInfo{"AU17_ChinRaiser", 17, "Chin Raiser", R::Lower, S::Both},
    ActionUnitInfo{"AU18_LipPucker", 18, "Lip Pucker", R::Lower, S::Both},
    ActionUnitInfo{"AU19_TongueShow", 19, "Tongue Show", R::Lower, S::Both},
    ActionUnitInfo{"AU20_LipStretcher", 20, "Lip Stretcher", R::Lower, S::Both},
    ActionUnitInfo{"AU22_LipFunneler", 22, "Lip Funneler", R::Lower, S::Both},
    ActionUnitInfo{"AU23_LipTightener", 23, "Lip Tightener", R::Lower, S::Both},
    ActionUnitInfo{"AU24_LipPressor", 24, "Lip Pressor", R::Lower, S::Both},
    ActionUnitInfo{"AU25_LipsPart", 25, "Lips Part", R::Lower, S::Both},
    ActionUnitInfo{"AU26_JawDrop", 26, "Jaw Drop", R::Lower, S::Both},
    ActionUnitInfo{"AU27_MouthStretch", 27, "Mouth Stretch", R::Lower, S::Both},
    ActionUnitInfo{"AU28_LipSuck", 28, "Lip Suck", R::Lower, S::Both},
    ActionUnitInfo{"AU29_JawThrust", 29, "Jaw Thrust", R::Lower, S::Both},
    ActionUnitInfo{"AU45_Blink_L", 45, "Blink", R::Upper, S::Left},
    ActionUnitInfo{"AU45_Blink_R", 45, "Blink", R::Upper, S::Right},
};

}  // namespace

std::span<const ActionUnitInfo> actionUnits() { return kActionUnits; }

std::optional<uint32_t> actionUnitIndex(std::string_view name) {
  for (uint32_t i = 0; i < kActionUnits.size(); ++i)
    if (kActionUnits[i].name == name) return i;
  return std::nullopt;
}

}  // namespace facial
