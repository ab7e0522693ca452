// Rig map files (data/rigmaps/*.json): a hand-written map from action units
// and emotions to a model's morph targets, and/or a calibration. A map that
// loads is applied to all-one inputs: the targets it drives must get finite
// weights inside the map's weight range.
#include <cmath>
#include <string>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "fuzz/fuzz_support.h"

namespace {

// Target names from the seeds' models (RobotExpressive, an ARKit face).
const std::vector<std::string> kTargets = {"Angry", "Surprised", "Sad", "jawOpen", "eyeBlink_L", "eyeBlink_R",
                                           "mouthSmile_L", "mouthSmile_R", "browInnerUp", "target_0"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = fuzz::writeInput("rigmap.json", data, size);
  auto file = facial::loadRigMapFile(path, kTargets);
  if (!file || !file->mapping) return 0;
  const facial::RigMapping& rig = *file->mapping;
  std::vector<float> au(facial::actionUnits().size(), 1.0f);
  std::vector<float> emotions(facial::kEmotionCount, 1.0f);
  std::vector<float> targets(rig.targetCount());
  if (!rig.apply(au, emotions, targets)) return 0;
  for (uint32_t t : rig.drivenTargets()) {
    const float w = targets[t];
    FUZZ_PROPERTY(std::isfinite(w) && w >= rig.minWeight() - 1e-4f && w <= rig.maxWeight() + 1e-4f,
                  "target weight " + std::to_string(w) + " outside [" + std::to_string(rig.minWeight()) + ", " +
                      std::to_string(rig.maxWeight()) + "]");
  }
  return 0;
}
