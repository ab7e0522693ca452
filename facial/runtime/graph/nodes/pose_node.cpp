#include "facial/runtime/graph/nodes/pose_node.h"

#include <cmath>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

using detail::NodeReader;

std::string_view vrmOverrideName(VrmOverride value) { return eng::nameOf(kVrmOverrideNames, value); }

std::optional<VrmOverride> vrmOverrideFromName(std::string_view name) { return eng::valueNamed(kVrmOverrideNames, name); }

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

namespace {

// "weights": an array with one weight per channel, or {"channel": weight}.
eng::Result<std::vector<float>> readWeights(const JsonNode& w, const ChannelSet& channels) {
  std::vector<float> weights(channels.size(), 0.0f);
  if (w.isArray()) {
    const size_t count = ENG_TRY_VALUE(w.size());
    if (count != channels.size())
      return w.error("has " + std::to_string(count) + " weights, the graph has " + std::to_string(channels.size()) +
                     " channels");
    for (size_t c = 0; c < count; ++c) weights[c] = ENG_TRY_VALUE(w.element(c).number());
    return weights;
  }
  if (!w.isObject()) return w.error("expected {\"channel\": weight} or an array of weights");
  for (const auto& [name, value] : ENG_TRY_VALUE(w.members())) {
    auto c = channels.find(name);
    if (!c) return value.error("'" + std::string(name) + "' is not a channel of this graph");
    weights[*c] = ENG_TRY_VALUE(value.number());
  }
  return weights;
}

}  // namespace

eng::Result<PoseNode> PoseNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "preset", "intensity", "weights", "scale", "overrideBlink"}));
  PoseNode node;
  if (auto preset = j.find("preset")) {
    if (j.has("weights")) return j.error("give either \"preset\" or \"weights\", not both");
    const std::string name = ENG_TRY_VALUE(preset->string());
    auto weights = presetPose(r.presets(), name, ENG_TRY_VALUE(j.numberOr("intensity", 1.0f)), r.channels());
    if (!weights) return preset->error(weights.error().message);
    node.weights = std::move(weights).value();
  } else if (auto w = j.find("weights")) {
    if (j.has("intensity"))
      return ENG_TRY_VALUE(j.at("intensity")).error("\"intensity\" applies to a preset; scale weights with \"scale\"");
    node.weights = ENG_TRY_VALUE(readWeights(*w, r.channels()));
  } else {
    return j.error("a pose needs \"preset\" or \"weights\"");
  }
  node.scale = ENG_TRY_VALUE(r.floatInput(j, "scale", 1.0f));
  if (auto o = j.find("overrideBlink")) {
    auto mode = vrmOverrideFromName(ENG_TRY_VALUE(o->string()));
    if (!mode) return o->error("unknown overrideBlink (expected " + eng::nameList(kVrmOverrideNames) + ")");
    node.overrideBlink = *mode;
  }
  return node;
}

}  // namespace facial
