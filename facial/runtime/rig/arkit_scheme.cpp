// Arkit52 scheme: FACS action units expressed in ARKit blend shapes.
#include <array>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

struct AuToArkit {
  std::string_view channel;
  std::string_view shape;  // canonical ARKit name
  float gain;
};

// Why these gains: ARKit shapes are captured at full muscle effort, so most
// units map 1:1. Exceptions:
//  - AU6 raises the cheeks and narrows the eye from below: cheekSquint plus a
//    little eyeSquint (the Duchenne crease).
//  - AU9 lifts the upper lip slightly with the nose wrinkle.
//  - AU17 pushes the lower lip up, which carries the upper lip a little.
//  - AU23 narrows and thins the lips: ARKit has no lip tightener, the closest
//    is rolling both lips in a bit with a slight pucker.
//  - AU25 parts the lips without much jaw: lower lip down, a hint of upper lip
//    and jaw.
//  - AU26 is a relaxed jaw drop; jawOpen at 1 is a wide-open mouth (AU27), so
//    AU26 reaches about 60% of it, and AU27 (mouth stretch) adds the rest.
//  - AU19 (tongue show) is tongueOut at half: the tip between the teeth, not
//    the whole tongue out.
//  - AU29 (jaw thrust) is not mapped to jawForward: nothing speaks or emotes
//    with it, and a driven target loses the model's own default weight
//    (facecap rests with jawForward 0.1, which closes its lips).
constexpr std::array kTable = {
    AuToArkit{"AU1_InnerBrowRaiser", "browInnerUp", 1.0f},
    AuToArkit{"AU2_OuterBrowRaiser_L", "browOuterUpLeft", 1.0f},
    AuToArkit{"AU2_OuterBrowRaiser_R", "browOuterUpRight", 1.0f},
    AuToArkit{"AU4_BrowLowerer", "browDownLeft", 1.0f},
    AuToArkit{"AU4_BrowLowerer", "browDownRight", 1.0f},
    AuToArkit{"AU5_UpperLidRaiser", "eyeWideLeft", 1.0f},
    AuToArkit{"AU5_UpperLidRaiser", "eyeWideRight", 1.0f},
    AuToArkit{"AU6_CheekRaiser", "cheekSquintLeft", 1.0f},
    AuToArkit{"AU6_CheekRaiser", "cheekSquintRight", 1.0f},
    AuToArkit{"AU6_CheekRaiser", "eyeSquintLeft", 0.25f},
    AuToArkit{"AU6_CheekRaiser", "eyeSquintRight", 0.25f},
    AuToArkit{"AU7_LidTightener", "eyeSquintLeft", 1.0f},
    AuToArkit{"AU7_LidTightener", "eyeSquintRight", 1.0f},
    AuToArkit{"AU9_NoseWrinkler", "noseSneerLeft", 1.0f},
    AuToArkit{"AU9_NoseWrinkler", "noseSneerRight", 1.0f},
    AuToArkit{"AU9_NoseWrinkler", "mouthUpperUpLeft", 0.2f},
    AuToArkit{"AU9_NoseWrinkler", "mouthUpperUpRight", 0.2f},
    AuToArkit{"AU10_UpperLipRaiser", "mouthUpperUpLeft", 1.0f},
    AuToArkit{"AU10_UpperLipRaiser", "mouthUpperUpRight", 1.0f},
    AuToArkit{"AU12_LipCornerPuller_L", "mouthSmileLeft", 1.0f},
    AuToArkit{"AU12_LipCornerPuller_R", "mouthSmileRight", 1.0f},
    AuToArkit{"AU15_LipCornerDepressor", "mouthFrownLeft", 1.0f},
    AuToArkit{"AU15_LipCornerDepressor", "mouthFrownRight", 1.0f},
    AuToArkit{"AU16_LowerLipDepressor", "mouthLowerDownLeft", 1.0f},
    AuToArkit{"AU16_LowerLipDepressor", "mouthLowerDownRight", 1.0f},
    AuToArkit{"AU17_ChinRaiser", "mouthShrugLower", 1.0f},
    AuToArkit{"AU17_ChinRaiser", "mouthShrugUpper", 0.4f},
    AuToArkit{"AU18_LipPucker", "mouthPucker", 1.0f},
    AuToArkit{"AU19_TongueShow", "tongueOut", 0.5f},
    AuToArkit{"AU20_LipStretcher", "mouthStretchLeft", 1.0f},
    AuToArkit{"AU20_LipStretcher", "mouthStretchRight", 1.0f},
    AuToArkit{"AU22_LipFunneler", "mouthFunnel", 1.0f},
    AuToArkit{"AU23_LipTightener", "mouthRollUpper", 0.35f},
    AuToArkit{"AU23_LipTightener", "mouthRollLower", 0.35f},
    AuToArkit{"AU23_LipTightener", "mouthPucker", 0.2f},
    AuToArkit{"AU24_LipPressor", "mouthPressLeft", 1.0f},
    AuToArkit{"AU24_LipPressor", "mouthPressRight", 1.0f},
    AuToArkit{"AU25_LipsPart", "mouthLowerDownLeft", 0.25f},
    AuToArkit{"AU25_LipsPart", "mouthLowerDownRight", 0.25f},
    AuToArkit{"AU25_LipsPart", "mouthUpperUpLeft", 0.1f},
    AuToArkit{"AU25_LipsPart", "mouthUpperUpRight", 0.1f},
    AuToArkit{"AU25_LipsPart", "jawOpen", 0.1f},
    AuToArkit{"AU26_JawDrop", "jawOpen", 0.6f},
    AuToArkit{"AU27_MouthStretch", "jawOpen", 0.4f},
    AuToArkit{"AU27_MouthStretch", "mouthStretchLeft", 0.3f},
    AuToArkit{"AU27_MouthStretch", "mouthStretchRight", 0.3f},
    AuToArkit{"AU28_LipSuck", "mouthRollUpper", 1.0f},
    AuToArkit{"AU28_LipSuck", "mouthRollLower", 1.0f},
    AuToArkit{"AU45_Blink_L", "eyeBlinkLeft", 1.0f},
    AuToArkit{"AU45_Blink_R", "eyeBlinkRight", 1.0f},
};

}  // namespace

SchemeRecognition recogniseArkit52(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  size_t suffixSpelt = 0, wordSpelt = 0;
  for (const std::string& name : targetNames) {
    ArkitSpelling spelling = ArkitSpelling::Unsided;
    if (!arkitIndex(name, &spelling)) continue;
    ++r.recognised;
    if (spelling == ArkitSpelling::SuffixLR) ++suffixSpelt;
    if (spelling == ArkitSpelling::LeftRight) ++wordSpelt;
  }
  r.detail = std::to_string(r.recognised) + " of 52 ARKit names, " +
             (suffixSpelt >= wordSpelt ? "_L/_R spelling" : "Left/Right spelling");
  return r;
}

void mapArkit52(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  const std::span<const std::string_view> canonical = arkitBlendShapeNames();
  // Every target spelling a shape is driven (a face and its eyelashes may both carry eyeBlink_L).
  for (uint32_t t = 0; t < names.size(); ++t) {
    const std::optional<uint32_t> shape = arkitIndex(names[t]);
    if (!shape) continue;
    for (const AuToArkit& row : kTable)
      if (row.shape == canonical[*shape]) builder.add(*actionUnitIndex(row.channel), t, row.gain);
  }
  builder.note("ARKit gaze, jaw sideways/forward, cheek puff, dimple, funnel, mouth sideways and tongue shapes "
               "have no FACS channel here and stay free for other drivers");
}

}  // namespace facial
