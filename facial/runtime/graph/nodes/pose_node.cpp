#include "facial/runtime/graph/nodes/pose_node.h"

#include <cmath>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

using detail::JsonNode;
using detail::NodeReader;

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

PoseNode PoseNode::read(const JsonNode& j, NodeReader& r) {
  j.allowOnly({"type", "name", "preset", "intensity", "weights", "scale", "overrideBlink"});
  PoseNode node;
  const uint32_t channels = r.channels().size();
  if (auto preset = j.find("preset")) {
    if (j.has("weights")) j.fail("give either \"preset\" or \"weights\", not both");
    auto weights = presetPose(r.presets(), preset->string(), j.numberOr("intensity", 1.0f), r.channels());
    if (!weights) preset->fail(weights.error().message);
    node.weights = std::move(weights).value();
  } else if (auto w = j.find("weights")) {
    if (j.has("intensity")) j.at("intensity").fail("\"intensity\" applies to a preset; scale weights with \"scale\"");
    node.weights.assign(channels, 0.0f);
    if (w->isArray()) {
      if (w->size() != channels)
        w->fail("has " + std::to_string(w->size()) + " weights, the graph has " + std::to_string(channels) +
                " channels");
      for (size_t c = 0; c < channels; ++c) node.weights[c] = (*w)[c].number();
    } else {
      if (!w->isObject()) w->fail("expected {\"channel\": weight} or an array of weights");
      for (auto it = w->raw().begin(); it != w->raw().end(); ++it) {
        auto c = r.channels().find(it.key());
        if (!c) w->at(it.key()).fail("'" + it.key() + "' is not a channel of this graph");
        node.weights[*c] = w->at(it.key()).number();
      }
    }
  } else {
    j.fail("a pose needs \"preset\" or \"weights\"");
  }
  node.scale = r.floatInput(j, "scale", 1.0f);
  if (auto o = j.find("overrideBlink")) {
    auto mode = vrmOverrideFromString(o->string());
    if (!mode) o->fail("unknown overrideBlink (expected none, block or blend)");
    node.overrideBlink = *mode;
  }
  return node;
}

}  // namespace facial
