#include "facial/runtime/graph/nodes/control_map_node.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"

namespace facial {

using detail::NodeReader;

ControlMapWeights controlMapWeights(float x, float y) {
  ControlMapWeights w;
  x = std::clamp(x, -1.0f, 1.0f);
  y = std::clamp(y, -1.0f, 1.0f);
  const float l1 = std::abs(x) + std::abs(y);
  if (l1 > 1.0f) {
    x /= l1;
    y /= l1;
  }
  w.x = x;
  w.y = y;
  if (x >= 0.0f) w.e3 = x;
  else w.e4 = std::abs(x);
  if (y >= 0.0f) w.e1 = y;
  else w.e2 = std::abs(y);
  w.neutral = std::max(0.0f, 1.0f - (w.e1 + w.e2 + w.e3 + w.e4));  // max: rounding of the projection only
  return w;
}

eng::Result<void> ControlMapNode::prepare(const BuildContext& ctx) {
  if (auto p = ctx.checkInput(x, "x"); !p) return p;
  return ctx.checkInput(y, "y");
}

void ControlMapNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  const ControlMapWeights w = controlMapWeights(ctx.read(x), ctx.read(y));
  const std::array<NodeIndex, 5> nodes = {neutral, e1, e2, e3, e4};
  const std::array<float, 5> weights = {w.neutral, w.e1, w.e2, w.e3, w.e4};
  ctx.evaluateWeightedSum(nodes, weights, out);
}

eng::Result<ControlMapNode> ControlMapNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "neutral", "up", "down", "right", "left", "x", "y"}));
  ControlMapNode m{.neutral = ENG_TRY_VALUE(r.nodeAt(j, "neutral")),
                   .e1 = ENG_TRY_VALUE(r.nodeAt(j, "up")),
                   .e2 = ENG_TRY_VALUE(r.nodeAt(j, "down")),
                   .e3 = ENG_TRY_VALUE(r.nodeAt(j, "right")),
                   .e4 = ENG_TRY_VALUE(r.nodeAt(j, "left"))};
  m.x = ENG_TRY_VALUE(r.floatInput(j, "x", 0.0f));
  m.y = ENG_TRY_VALUE(r.floatInput(j, "y", 0.0f));
  return m;
}

}  // namespace facial
