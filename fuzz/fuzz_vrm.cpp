// VRM 1.0 (VRMC_vrm) and 0.x (VRM.blendShapeMaster) expressions, read the
// way the face loader reads them (facial/importers/vrm_import.h), and the VRM rig
// built over the model's morph targets when the two agree.
#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "importers/vrm_import.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "fuzz/fuzz_support.h"

namespace {

constexpr eng::GltfLoadLimits kLimits{.maxFileBytes = size_t{8} << 20,
                                      .maxDecodedBytes = size_t{64} << 20,
                                      .maxImagePixels = size_t{4} << 20};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = fuzz::writeInput("input.vrm", data, size);
  auto vrm = importers::findVrmExpressions(path);
  if (!vrm || !*vrm) return 0;
  auto set = std::make_shared<const facial::VrmExpressionSet>(std::move(**vrm));
  auto model = eng::loadModel(path, kLimits);
  if (!model) return 0;
  const eng::WeightLayout layout(*model);
  bool sameLayout = set->meshTargetOffsets.size() == size_t(layout.meshCount()) + 1;
  for (int m = 0; sameLayout && m <= layout.meshCount(); ++m) sameLayout = set->meshTargetOffsets[m] == layout.offset(m);
  if (!sameLayout) return 0;  // the face loader refuses this pair with a message
  (void)facial::buildVrmRigMapping(set, layout.names());
  return 0;
}
