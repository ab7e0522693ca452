// Candide3 scheme: the mask's animation units as imported by facial_bake.
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/candide_units.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {

SchemeRecognition recogniseCandide3(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  for (const std::string& name : targetNames) r.recognised += findCandideUnit(name) ? 1 : 0;
  r.detail = std::to_string(r.recognised) + " of the " + std::to_string(candideAnimationUnits().size()) +
             " CANDIDE-3 animation units";
  return r;
}

void mapCandide3(RigMappingBuilder& builder) {
  // Parameters are signed (a negative lip corner depressor is a smile). They
  // are linear offsets, not sculpted end poses, so the range is as wide as the
  // strength calibration may raise a unit: at 1 the mask's brows, lids and lip
  // corners move 0.2-0.6 of the reference reach, and a [-1, 1] clamp undid the
  // calibration's x1.6 on every state at full intensity.
  const float reach = RigCalibrationOptions{}.maxScale;
  builder.setWeightRange(-reach, reach);
  const std::span<const std::string> names = builder.targetNames();
  for (uint32_t t = 0; t < names.size(); ++t) {
    const CandideAnimationUnit* unit = findCandideUnit(names[t]);
    if (!unit) continue;
    for (const CandideChannelGain& g : unit->drive) builder.add(*actionUnitIndex(g.channel), t, g.gain);
  }
  builder.note("CANDIDE-3 has no lip corner puller: AU12 drives 'Lip corner depressor' negatively");
  builder.note("CANDIDE-3 jaw z-push / x-push realise AU29 / AU30, which the channel vocabulary lacks");
  builder.note("CANDIDE-3 shape units (SU_*) are identity, not expression: bake them into the mask with "
               "--shape NAME=VALUE");
}

}  // namespace facial
