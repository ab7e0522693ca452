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

}  // namespace

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

std::vector<std::string> VrmExpressionSet::expressionNames() const {
  std::vector<std::string> names;
  names.reserve(expressions.size());
  for (const VrmExpression& e : expressions) names.push_back(e.name);
  return names;
}

eng::Result<void> VrmExpressionSet::validate() const {
  if (meshTargetOffsets.empty() || meshTargetOffsets.front() != 0 || meshTargetOffsets.back() != targetNames.size())
    return eng::makeError("VRM expressions: mesh target offsets must run from 0 to the " +
                          std::to_string(targetNames.size()) + " targets");
  for (size_t m = 0; m + 1 < meshTargetOffsets.size(); ++m)
    if (meshTargetOffsets[m] > meshTargetOffsets[m + 1])
      return eng::makeError("VRM expressions: mesh target offsets decrease at mesh " + std::to_string(m));
  for (const VrmExpression& e : expressions)
    if (size_t(e.firstBind) + e.bindCount > binds.size())
      return eng::makeError("VRM expressions: '" + e.name + "' binds [" + std::to_string(e.firstBind) + ", " +
                            std::to_string(e.firstBind + e.bindCount) + ") of " + std::to_string(binds.size()));
  for (size_t b = 0; b < binds.size(); ++b) {
    if (binds[b].target >= targetNames.size())
      return eng::makeError("VRM expressions: bind " + std::to_string(b) + " targets " +
                            std::to_string(binds[b].target) + " of " + std::to_string(targetNames.size()));
    if (!std::isfinite(binds[b].weight))
      return eng::makeError("VRM expressions: bind " + std::to_string(b) + " has a non-finite weight");
  }
  return {};
}

eng::Result<void> VrmExpressionSet::apply(std::span<const float> expressionWeights,
                                          std::span<float> targetWeights) const {
  if (expressionWeights.size() != expressions.size() || targetWeights.size() != targetNames.size())
    return eng::makeError("VRM expressions: apply got " + std::to_string(expressionWeights.size()) +
                          " expression weights and " + std::to_string(targetWeights.size()) +
                          " target weights; expected " + std::to_string(expressions.size()) + " and " +
                          std::to_string(targetNames.size()));
  for (size_t i = 0; i < expressionWeights.size(); ++i)
    if (!std::isfinite(expressionWeights[i]))
      return eng::makeError("VRM expressions: weight of '" + expressions[i].name + "' is not finite");

  // Per procedural group: blocked by any 'block' expression with weight > 0,
  // else attenuated by the saturated sum of the 'blend' expressions' weights.
  constexpr size_t kGroups = 4;
  std::array<bool, kGroups> blocked{};
  std::array<float, kGroups> blended{};
  for (size_t i = 0; i < expressions.size(); ++i) {
    const VrmExpression& e = expressions[i];
    const float w = resolvedWeight(e, expressionWeights[i]);
    if (w <= 0.0f) continue;
    for (VrmProceduralGroup g : {VrmProceduralGroup::Blink, VrmProceduralGroup::LookAt, VrmProceduralGroup::Mouth}) {
      if (g == e.group) continue;  // an override on its own group is invalid per spec
      const VrmOverride o = overrideOf(e, g);
      if (o == VrmOverride::Block) blocked[static_cast<size_t>(g)] = true;
      else if (o == VrmOverride::Blend) blended[static_cast<size_t>(g)] += w;
    }
  }

  std::fill(targetWeights.begin(), targetWeights.end(), 0.0f);
  for (size_t i = 0; i < expressions.size(); ++i) {
    const VrmExpression& e = expressions[i];
    float w = resolvedWeight(e, expressionWeights[i]);
    if (e.group != VrmProceduralGroup::None) {
      const size_t g = static_cast<size_t>(e.group);
      const float factor = blocked[g] ? 0.0f : 1.0f - saturate(blended[g]);
      // A binary expression must stay 0 or 1: any override suppresses it.
      w = e.isBinary ? (factor < 1.0f ? 0.0f : w) : w * factor;
    }
    if (w == 0.0f) continue;
    for (uint32_t b = e.firstBind; b < e.firstBind + e.bindCount; ++b) targetWeights[binds[b].target] += binds[b].weight * w;
  }
  return {};
}

}  // namespace facial
