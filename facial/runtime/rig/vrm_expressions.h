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
//    are stored already divided by 100);
//  - material colour binds move a material's colour from its own value towards
//    targetValue by the (effective) expression weight, and the deltas of
//    several expressions add: value = rest + sum_e w_e * (target_e - rest), as
//    three-vrm's VRMExpressionMaterialColorBind and UniVRM's material value
//    merger do (VRM 0.x materialValues likewise); texture transform binds move
//    the UV scale from the material's own (1,1) and the offset from (0,0)
//    towards theirs the same way (applyMaterials).
// Parsing the glTF JSON lives in facial_bake (vrm_import.h); this part stays
// pure. Targets are flat and mesh-major like eng::WeightLayout: mesh m's
// targets start at meshTargetOffsets[m].
#include <array>
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

// VRM 1.0 materialColorBinds[].type; VRM 0.x materialValues' propertyName
// _Color, _EmissionColor, _ShadeColor, _SphereAdd (matcap), _RimColor, _OutlineColor.
enum class VrmMaterialColorType : uint8_t { Color, EmissionColor, ShadeColor, MatcapColor, RimColor, OutlineColor };
std::string_view vrmMaterialColorTypeName(VrmMaterialColorType type);

struct VrmMaterialColorBind {
  uint32_t material = 0;  // glTF material index
  VrmMaterialColorType type = VrmMaterialColorType::Color;
  std::array<float, 4> targetValue{};  // linear RGBA (RGB for emission, A ignored)
};

// KHR_texture_transform-like: uv' = uv * scale + offset.
struct VrmTextureTransformBind {
  uint32_t material = 0;
  std::array<float, 2> scale{1.0f, 1.0f};
  std::array<float, 2> offset{0.0f, 0.0f};
};

// A material's expression-driven state (applyMaterials output).
struct VrmMaterialState {
  std::array<float, 4> color{};            // base colour factor
  std::array<float, 3> emission{};         // emissive factor
  std::array<float, 3> shade{};            // MToon shade colour (linear RGB)
  std::array<float, 3> rim{};              // MToon parametric rim colour
  std::array<float, 3> outline{};          // MToon outline colour
  std::array<float, 3> matcap{};           // MToon matcap factor
  std::array<float, 2> uvScale{1.0f, 1.0f};
  std::array<float, 2> uvOffset{0.0f, 0.0f};
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
  uint32_t firstMaterialColorBind = 0;  // into VrmExpressionSet::materialColorBinds
  uint32_t materialColorBindCount = 0;
  uint32_t firstTextureTransformBind = 0;  // into VrmExpressionSet::textureTransformBinds
  uint32_t textureTransformBindCount = 0;
};

// How a gaze angle becomes an eye bone angle or a lookAt expression weight
// (VRMC_vrm 1.0 lookAt.rangeMap*, VRM 0.x firstPerson.lookAt* {xRange, yRange}):
// |degrees| clamped to inputMaxValue, / inputMaxValue * outputScale. The 0.x
// curve is taken as linear.
struct VrmLookAtRangeMap {
  float inputMaxValue = 90.0f;  // degrees
  float outputScale = 1.0f;     // degrees (bone type) or expression weight
  float map(float degrees) const;
};

enum class VrmLookAtType : uint8_t { Expression, Bone };

// The file's lookAt: which applier drives the eyes and the range of each
// direction. Without one in the file: expression type, 90 degrees -> weight 1.
struct VrmLookAt {
  VrmLookAtType type = VrmLookAtType::Expression;
  VrmLookAtRangeMap horizontalInner, horizontalOuter, verticalDown, verticalUp;
};

// The procedural group a VRM 1.0 / 0.x preset name belongs to.
VrmProceduralGroup vrmProceduralGroup(std::string_view expressionName);

struct VrmExpressionSet {
  int specVersion = 1;                      // 0 for VRM 0.x, 1 for VRMC_vrm 1.0
  std::vector<VrmExpression> expressions;
  std::vector<VrmMorphBind> binds;
  std::vector<VrmMaterialColorBind> materialColorBinds;
  std::vector<VrmTextureTransformBind> textureTransformBinds;
  uint32_t materialCount = 0;               // glTF materials: the range of material binds
  std::vector<std::string> targetNames;     // flat, mesh-major ("<mesh>/<target>")
  std::vector<uint32_t> meshTargetOffsets;  // glTF mesh count + 1
  std::vector<std::string> warnings;        // e.g. material binds that are not applied
  VrmLookAt lookAt;                         // how the lookLeft/Right/Up/Down expressions are reached

  size_t targetCount() const { return targetNames.size(); }
  // Expression names in order: the "target list" a RigMapping is built over.
  std::vector<std::string> expressionNames() const;

  // Ranges, indices, finite weights.
  eng::Result<void> validate() const;

  // expressionWeights.size() == expressions.size(); targetWeights.size() ==
  // targetCount(). Every target is written (0 where no expression binds it).
  // No allocation. Errors name the sizes / the non-finite expression.
  eng::Result<void> apply(std::span<const float> expressionWeights, std::span<float> targetWeights) const;

  // The expression weights after clamping, isBinary and the override rules
  // (what apply() multiplies the binds with). Same sizes as expressions.
  eng::Result<void> effectiveWeights(std::span<const float> expressionWeights, std::span<float> effective) const;

  // effective: effectiveWeights()' output; rest: every material's own state
  // (materialCount entries); out (same size): rest moved by the material
  // colour and texture transform binds of the weighted expressions: base
  // colour, emission and MToon's shade, matcap, rim and outline colours
  // (drawn on MToon materials). No allocation (per frame).
  eng::Result<void> applyMaterials(std::span<const float> effective, std::span<const VrmMaterialState> rest,
                                   std::span<VrmMaterialState> out) const;
  bool hasMaterialBinds() const { return !materialColorBinds.empty() || !textureTransformBinds.empty(); }
  // Whether expression e changes anything at weight 1: a morph bind of some
  // weight, or a material colour or texture transform bind. A file exported
  // from a model without blend shapes keeps the presets, binding nothing.
  bool moves(size_t e) const;
};

}  // namespace facial
