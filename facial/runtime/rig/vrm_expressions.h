#pragma once
// VRM expressions at runtime: expression weights -> morph target weights,
// following the VRMC_vrm 1.0 expression rules (vrm-c/vrm-specification,
// specification/VRMC_vrm-1.0/expressions.md):
//  - input weights are clamped to [0,1]; isBinary expressions output 1 above
//    0.5, else 0;
//  - procedural groups: blink (blink, blinkLeft, blinkRight), lookAt (lookUp/
//    Down/Left/Right), mouth (aa, ih, ou, ee, oh). An expression with
//    overrideBlink/LookAt/Mouth = block zeroes that group while its (binary-
//    resolved) weight is > 0; = blend scales it by 1 - saturate(sum of blending
//    weights). An override on an expression of the same group is ignored; a
//    binary overridden expression is suppressed completely by any override;
//  - morph weights accumulate bind.weight * expression weight (binds of VRM 0.x
//    are stored already divided by 100).
// Parsing the glTF JSON lives in facial_bake (vrm_import.h); this part stays
// pure. Targets are flat and mesh-major like eng::WeightLayout: mesh m's
// targets start at meshTargetOffsets[m].
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"

namespace facial {

enum class VrmOverride : uint8_t { None, Block, Blend };
enum class VrmProceduralGroup : uint8_t { None, Blink, LookAt, Mouth };

struct VrmMorphBind {
  uint32_t target = 0;  // flat target index
  float weight = 0.0f;  // [0,1]
};

struct VrmExpression {
  std::string name;            // VRM 1.0 preset / custom name, VRM 0.x presetName or group name
  bool isPreset = false;
  bool isBinary = false;
  VrmOverride overrideBlink = VrmOverride::None;
  VrmOverride overrideLookAt = VrmOverride::None;
  VrmOverride overrideMouth = VrmOverride::None;
  VrmProceduralGroup group = VrmProceduralGroup::None;  // from the name
  uint32_t firstBind = 0;  // into VrmExpressionSet::binds
  uint32_t bindCount = 0;
};

// The procedural group a VRM 1.0 / 0.x preset name belongs to.
VrmProceduralGroup vrmProceduralGroup(std::string_view expressionName);

struct VrmExpressionSet {
  int specVersion = 1;                      // 0 for VRM 0.x, 1 for VRMC_vrm 1.0
  std::vector<VrmExpression> expressions;
  std::vector<VrmMorphBind> binds;
  std::vector<std::string> targetNames;     // flat, mesh-major ("<mesh>/<target>")
  std::vector<uint32_t> meshTargetOffsets;  // glTF mesh count + 1
  std::vector<std::string> warnings;        // e.g. material binds that are not applied

  size_t targetCount() const { return targetNames.size(); }
  // Expression names in order: the "target list" a RigMapping is built over.
  std::vector<std::string> expressionNames() const;

  // Ranges, indices, finite weights.
  eng::Result<void> validate() const;

  // expressionWeights.size() == expressions.size(); targetWeights.size() ==
  // targetCount(). Every target is written (0 where no expression binds it).
  // No allocation. Errors name the sizes / the non-finite expression.
  eng::Result<void> apply(std::span<const float> expressionWeights, std::span<float> targetWeights) const;
};

}  // namespace facial
