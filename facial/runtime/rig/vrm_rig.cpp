// buildVrmRigMapping / attachExpressionStage: a VRM model's rig is detected
// over its expressions, and the expressions' binds carry it to the morph targets.
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

eng::Result<RigMapping> attachExpressionStage(const RigMapping& rows, std::shared_ptr<const VrmExpressionSet> stage,
                                              std::span<const std::string> morphTargetNames) {
  if (!stage) return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: no expression stage given");
  RigMappingBuilder builder = RigMappingBuilder::startingFrom(rows);
  builder.setExpressionStage(std::move(stage), std::vector<std::string>(morphTargetNames.begin(), morphTargetNames.end()));
  return builder.build();
}

eng::Result<RigMapping> buildVrmRigMapping(std::shared_ptr<const VrmExpressionSet> vrm,
                                           std::span<const std::string> morphTargetNames,
                                           const RigMappingOptions& options) {
  if (!vrm) return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: no VRM expressions given");
  if (vrm->targetCount() != morphTargetNames.size())
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: the VRM expressions address " + std::to_string(vrm->targetCount()) +
                          " morph targets, the model has " + std::to_string(morphTargetNames.size()));
  const std::vector<std::string> names = vrm->expressionNames();
  auto rows = buildRigMapping(names, options);
  if (!rows) return rows.error();
  if (rows->scheme() == RigScheme::Custom) return attachExpressionStage(*rows, vrm, morphTargetNames);
  // Speech again, now that the stage tells which mouth expressions bind nothing.
  RigMappingBuilder builder = RigMappingBuilder::startingFrom(*rows, true, false);
  builder.setExpressionStage(std::move(vrm), std::vector<std::string>(morphTargetNames.begin(), morphTargetNames.end()));
  mapSpeech(builder, rows->scheme());
  return builder.build();
}

}  // namespace facial
