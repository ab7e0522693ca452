#include "facial/runtime/rig/vrm_expressions.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

// Weight after clamping and isBinary, before any override.
float resolvedWeight(const VrmExpression& e, float input) {
  const float w = saturate(input);
  return e.isBinary ? (w > 0.5f ? 1.0f : 0.0f) : w;
}

VrmOverride overrideOf(const VrmExpression& e, VrmProceduralGroup group) {
  switch (group) {
    case VrmProceduralGroup::Blink: return e.overrideBlink;
    case VrmProceduralGroup::LookAt: return e.overrideLookAt;
    case VrmProceduralGroup::Mouth: return e.overrideMouth;
    case VrmProceduralGroup::None: break;
  }
  return VrmOverride::None;
}

// Per procedural group: blocked by any 'block' expression with weight > 0,
// else attenuated by the saturated sum of the 'blend' expressions' weights.
struct Overrides {
  static constexpr size_t kGroups = 4;
  std::array<bool, kGroups> blocked{};
  std::array<float, kGroups> blended{};

  // An expression's weight after clamping, isBinary and the overrides of its group.
  float effective(const VrmExpression& e, float input) const {
    const float w = resolvedWeight(e, input);
    if (e.group == VrmProceduralGroup::None) return w;
    const size_t g = static_cast<size_t>(e.group);
    const float factor = blocked[g] ? 0.0f : 1.0f - saturate(blended[g]);
    // A binary expression must stay 0 or 1: any override suppresses it.
    return e.isBinary ? (factor < 1.0f ? 0.0f : w) : w * factor;
  }
};

Overrides collectOverrides(std::span<const VrmExpression> expressions, std::span<const float> weights) {
  Overrides o;
  for (size_t i = 0; i < expressions.size(); ++i) {
    const VrmExpression& e = expressions[i];
    const float w = resolvedWeight(e, weights[i]);
    if (w <= 0.0f) continue;
    for (VrmProceduralGroup g : {VrmProceduralGroup::Blink, VrmProceduralGroup::LookAt, VrmProceduralGroup::Mouth}) {
      if (g == e.group) continue;  // an override on its own group is invalid per spec
      const VrmOverride kind = overrideOf(e, g);
      if (kind == VrmOverride::Block) o.blocked[static_cast<size_t>(g)] = true;
      else if (kind == VrmOverride::Blend) o.blended[static_cast<size_t>(g)] += w;
    }
  }
  return o;
}

eng::Result<void> checkFinite(const VrmExpressionSet& set, std::span<const float> weights) {
  for (size_t i = 0; i < weights.size() && i < set.expressions.size(); ++i)
    if (!std::isfinite(weights[i]))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "VRM expressions: weight of '" + set.expressions[i].name + "' is not finite");
  return {};
}

}  // namespace

float VrmLookAtRangeMap::map(float degrees) const {
  if (!(inputMaxValue > 0.0f)) return 0.0f;
  return std::min(std::abs(degrees), inputMaxValue) / inputMaxValue * outputScale;
}

VrmProceduralGroup vrmProceduralGroup(std::string_view name) {
  const std::string k = asciiLower(name);
  for (std::string_view n : {"blink", "blinkleft", "blinkright", "blink_l", "blink_r"})
    if (k == n) return VrmProceduralGroup::Blink;
  for (std::string_view n : {"lookup", "lookdown", "lookleft", "lookright"})
    if (k == n) return VrmProceduralGroup::LookAt;
  for (std::string_view n : {"aa", "ih", "ou", "ee", "oh", "a", "i", "u", "e", "o"})
    if (k == n) return VrmProceduralGroup::Mouth;
  return VrmProceduralGroup::None;
}

std::string_view vrmMaterialColorTypeName(VrmMaterialColorType type) {
  switch (type) {
    case VrmMaterialColorType::Color: return "color";
    case VrmMaterialColorType::EmissionColor: return "emissionColor";
    case VrmMaterialColorType::ShadeColor: return "shadeColor";
    case VrmMaterialColorType::MatcapColor: return "matcapColor";
    case VrmMaterialColorType::RimColor: return "rimColor";
    case VrmMaterialColorType::OutlineColor: return "outlineColor";
  }
  return "?";
}

bool VrmExpressionSet::moves(size_t e) const {
  if (e >= expressions.size()) return false;
  const VrmExpression& x = expressions[e];
  if (x.materialColorBindCount > 0 || x.textureTransformBindCount > 0) return true;
  for (uint32_t b = x.firstBind; b < x.firstBind + x.bindCount && b < binds.size(); ++b)
    if (binds[b].weight > 0.0f) return true;
  return false;
}

std::vector<std::string> VrmExpressionSet::expressionNames() const {
  std::vector<std::string> names;
  names.reserve(expressions.size());
  for (const VrmExpression& e : expressions) names.push_back(e.name);
  return names;
}

eng::Result<void> VrmExpressionSet::validate() const {
  if (meshTargetOffsets.empty() || meshTargetOffsets.front() != 0 || meshTargetOffsets.back() != targetNames.size())
    return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: mesh target offsets must run from 0 to the " +
                          std::to_string(targetNames.size()) + " targets");
  for (size_t m = 0; m + 1 < meshTargetOffsets.size(); ++m)
    if (meshTargetOffsets[m] > meshTargetOffsets[m + 1])
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: mesh target offsets decrease at mesh " + std::to_string(m));
  for (const VrmExpression& e : expressions)
    if (size_t(e.firstBind) + e.bindCount > binds.size())
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: '" + e.name + "' binds [" + std::to_string(e.firstBind) + ", " +
                            std::to_string(e.firstBind + e.bindCount) + ") of " + std::to_string(binds.size()));
  for (const VrmExpression& e : expressions) {
    if (size_t(e.firstMaterialColorBind) + e.materialColorBindCount > materialColorBinds.size() ||
        size_t(e.firstTextureTransformBind) + e.textureTransformBindCount > textureTransformBinds.size())
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: '" + e.name + "' material binds are out of range");
  }
  for (const VrmMaterialColorBind& b : materialColorBinds) {
    if (b.material >= materialCount)
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: a material colour bind addresses material " + std::to_string(b.material) +
                            " of " + std::to_string(materialCount));
    for (float v : b.targetValue)
      if (!std::isfinite(v)) return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: a material colour bind has a non-finite value");
  }
  for (const VrmTextureTransformBind& b : textureTransformBinds) {
    if (b.material >= materialCount)
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: a texture transform bind addresses material " +
                            std::to_string(b.material) + " of " + std::to_string(materialCount));
    for (float v : {b.scale[0], b.scale[1], b.offset[0], b.offset[1]})
      if (!std::isfinite(v)) return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: a texture transform bind has a non-finite value");
  }
  for (size_t b = 0; b < binds.size(); ++b) {
    if (binds[b].target >= targetNames.size())
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: bind " + std::to_string(b) + " targets " +
                            std::to_string(binds[b].target) + " of " + std::to_string(targetNames.size()));
    if (!std::isfinite(binds[b].weight))
      return eng::makeError(eng::ErrorKind::Malformed, "VRM expressions: bind " + std::to_string(b) + " has a non-finite weight");
  }
  return {};
}

eng::Result<void> VrmExpressionSet::effectiveWeights(std::span<const float> expressionWeights,
                                                     std::span<float> effective) const {
  if (expressionWeights.size() != expressions.size() || effective.size() != expressions.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "VRM expressions: got " + std::to_string(expressionWeights.size()) +
                          " expression weights and room for " + std::to_string(effective.size()) + "; expected " +
                          std::to_string(expressions.size()));
  if (auto finite = checkFinite(*this, expressionWeights); !finite) return finite;
  const Overrides overrides = collectOverrides(expressions, expressionWeights);
  for (size_t i = 0; i < expressions.size(); ++i) effective[i] = overrides.effective(expressions[i], expressionWeights[i]);
  return {};
}

eng::Result<void> VrmExpressionSet::apply(std::span<const float> expressionWeights,
                                          std::span<float> targetWeights) const {
  if (expressionWeights.size() != expressions.size() || targetWeights.size() != targetNames.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "VRM expressions: apply got " + std::to_string(expressionWeights.size()) +
                          " expression weights and " + std::to_string(targetWeights.size()) +
                          " target weights; expected " + std::to_string(expressions.size()) + " and " +
                          std::to_string(targetNames.size()));
  if (auto finite = checkFinite(*this, expressionWeights); !finite) return finite;
  const Overrides overrides = collectOverrides(expressions, expressionWeights);
  std::fill(targetWeights.begin(), targetWeights.end(), 0.0f);
  for (size_t i = 0; i < expressions.size(); ++i) {
    const VrmExpression& e = expressions[i];
    const float w = overrides.effective(e, expressionWeights[i]);
    if (w == 0.0f) continue;
    for (uint32_t b = e.firstBind; b < e.firstBind + e.bindCount; ++b) targetWeights[binds[b].target] += binds[b].weight * w;
  }
  return {};
}

eng::Result<void> VrmExpressionSet::applyMaterials(std::span<const float> effective,
                                                   std::span<const VrmMaterialState> rest,
                                                   std::span<VrmMaterialState> materials) const {
  if (rest.size() != materialCount || materials.size() != materialCount)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "VRM expressions: " + std::to_string(rest.size()) + " material states given and room for " +
                          std::to_string(materials.size()) + ", the model has " + std::to_string(materialCount) +
                          " materials");
  if (effective.size() != expressions.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "VRM expressions: " + std::to_string(effective.size()) + " effective weights given, expected " +
                          std::to_string(expressions.size()));
  if (auto finite = checkFinite(*this, effective); !finite) return finite;
  // Deltas from every material's own state, so several expressions add up.
  std::copy(rest.begin(), rest.end(), materials.begin());
  for (size_t i = 0; i < expressions.size(); ++i) {
    const VrmExpression& e = expressions[i];
    const float w = effective[i];
    if (w == 0.0f) continue;
    for (uint32_t b = e.firstMaterialColorBind; b < e.firstMaterialColorBind + e.materialColorBindCount; ++b) {
      const VrmMaterialColorBind& bind = materialColorBinds[b];
      VrmMaterialState& m = materials[bind.material];
      const VrmMaterialState& r = rest[bind.material];
      auto moveRgb = [&](std::array<float, 3>& moved, const std::array<float, 3>& own) {
        for (size_t c = 0; c < 3; ++c) moved[c] += w * (bind.targetValue[c] - own[c]);
      };
      switch (bind.type) {
        case VrmMaterialColorType::Color:
          for (size_t c = 0; c < 4; ++c) m.color[c] += w * (bind.targetValue[c] - r.color[c]);
          break;
        case VrmMaterialColorType::EmissionColor: moveRgb(m.emission, r.emission); break;
        case VrmMaterialColorType::ShadeColor: moveRgb(m.shade, r.shade); break;
        case VrmMaterialColorType::RimColor: moveRgb(m.rim, r.rim); break;
        case VrmMaterialColorType::OutlineColor: moveRgb(m.outline, r.outline); break;
        case VrmMaterialColorType::MatcapColor: moveRgb(m.matcap, r.matcap); break;
      }
    }
    for (uint32_t b = e.firstTextureTransformBind; b < e.firstTextureTransformBind + e.textureTransformBindCount; ++b) {
      const VrmTextureTransformBind& bind = textureTransformBinds[b];
      VrmMaterialState& m = materials[bind.material];
      const VrmMaterialState& r = rest[bind.material];
      for (size_t c = 0; c < 2; ++c) {
        m.uvScale[c] += w * (bind.scale[c] - r.uvScale[c]);
        m.uvOffset[c] += w * (bind.offset[c] - r.uvOffset[c]);
      }
    }
  }
  return {};
}

}  // namespace facial
