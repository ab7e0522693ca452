#include "facial/runtime/graph/nodes/pose_node.h"

#include <cmath>

#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/rig/json_document.h"  // formatNumber

namespace facial {

std::string_view toString(VrmOverride mode) {
  switch (mode) {
    case VrmOverride::None: return "none";
    case VrmOverride::Block: return "block";
    case VrmOverride::Blend: return "blend";
  }
  return "none";
}

std::optional<VrmOverride> vrmOverrideFromString(std::string_view name) {
  for (VrmOverride m : {VrmOverride::None, VrmOverride::Block, VrmOverride::Blend})
    if (toString(m) == name) return m;
  return std::nullopt;
}

eng::Result<void> PoseNode::prepare(const BuildContext& ctx) {
  if (weights.size() != ctx.channels.size())
    return ctx.problem("weights", "has " + std::to_string(weights.size()) + " entries, the graph has " +
                                      std::to_string(ctx.channels.size()) + " channels");
  for (size_t c = 0; c < weights.size(); ++c)
    if (!std::isfinite(weights[c]) || weights[c] < 0.0f || weights[c] > 1.0f)
      return ctx.problem("weights", "channel '" + ctx.channels[static_cast<uint32_t>(c)].name + "' weight " +
                                        formatNumber(weights[c]) + " is not in [0,1]");
  return ctx.checkInput(scale, "scale");
}

void PoseNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  const float s = ctx.read(scale);
  const size_t channels = weights.size();
  for (size_t c = 0; c < channels; ++c) out[c] = s * weights[c];
  out[channels + kLaneOverrideBlinkBlock] = overrideBlink == VrmOverride::Block ? s : 0.0f;
  out[channels + kLaneOverrideBlinkBlend] = overrideBlink == VrmOverride::Blend ? s : 0.0f;
}

}  // namespace facial
