#include "facial/runtime/graph/nodes/bilinear_node.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/graph/pose_jobs.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

using detail::NodeReader;

void BilinearNode::inputs(std::vector<NodeIndex>& out) const {
  out.insert(out.end(), shape1.begin(), shape1.end());
  out.insert(out.end(), shape2.begin(), shape2.end());
}

eng::Result<void> BilinearNode::prepare(const BuildContext& ctx) {
  if (shape1.size() < 2 || shape1.size() != shape2.size())
    return ctx.problem("shapes", "needs two rows (face shapes) of the same length >= 2 (expressions), got " +
                                     std::to_string(shape1.size()) + " and " + std::to_string(shape2.size()));
  if (!std::isfinite(duration) || duration <= 0.0f)
    return ctx.problem("duration", "must be a finite number > 0 (got " + formatNumber(duration) + ")");
  if (auto p = ctx.checkInput(shape, "shape"); !p) return p;
  return ctx.checkParameter(expression, ParameterType::Float, "expression");
}

BilinearNode::State BilinearNode::makeState(const GraphDefinition& definition, NodeIndex, uint64_t) const {
  State state;
  state.from1.assign(definition.poseStride(), 0.0f);
  state.from2.assign(definition.poseStride(), 0.0f);
  return state;
}

void BilinearNode::reset(State& state) const {
  state.started = false;
  state.progress = 1.0f;
}

void BilinearNode::evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const {
  State& state = ctx.state<State>(self);
  const float selected = std::round(ctx.parameters[expression]);
  const uint32_t column = static_cast<uint32_t>(std::clamp(selected, 0.0f, static_cast<float>(shape1.size() - 1)));
  ScratchPose to1(ctx.scratch);
  ScratchPose to2(ctx.scratch);
  if (!state.started) {
    state.started = true;
    state.target = column;
    state.progress = 1.0f;
  } else if (column != state.target) {
    // Re-base on what is on screen: from_i = t1 from_i + t2 to_i.
    const float t2 = curve(state.progress);
    ctx.evaluate(shape1[state.target], to1.pose());
    ctx.evaluate(shape2[state.target], to2.pose());
    LerpPoseJob{.a = state.from1, .b = to1.pose(), .t = t2, .out = state.from1}.Run();
    LerpPoseJob{.a = state.from2, .b = to2.pose(), .t = t2, .out = state.from2}.Run();
    state.target = column;
    state.progress = 0.0f;
  }
  state.progress = std::min(1.0f, state.progress + ctx.dt / duration);
  ctx.evaluate(shape1[state.target], to1.pose());
  ctx.evaluate(shape2[state.target], to2.pose());
  BilinearPoseJob{.q11 = state.from1,
                  .q12 = to1.pose(),
                  .q21 = state.from2,
                  .q22 = to2.pose(),
                  .s2 = std::clamp(ctx.read(shape), 0.0f, 1.0f),
                  .t2 = curve(state.progress),
                  .out = out}
      .Run();
}

eng::Result<BilinearNode> BilinearNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "shapes", "shape", "expression", "duration", "curve"}));
  BilinearNode b;
  const JsonNode shapes = ENG_TRY_VALUE(j.at("shapes"));
  const size_t rows = ENG_TRY_VALUE(shapes.size());
  if (rows != 2) return shapes.error("expected two rows (face shapes), got " + std::to_string(rows));
  for (size_t s = 0; s < 2; ++s) {
    std::vector<NodeIndex>& row = s == 0 ? b.shape1 : b.shape2;
    const JsonNode expressions = shapes.element(s);
    const size_t count = ENG_TRY_VALUE(expressions.size());
    for (size_t e = 0; e < count; ++e) row.push_back(ENG_TRY_VALUE(r.node(expressions.element(e))));
  }
  b.shape = ENG_TRY_VALUE(r.floatInput(j, "shape", 0.0f));
  b.expression = ENG_TRY_VALUE(r.parameter(ENG_TRY_VALUE(j.at("expression"))));
  b.duration = ENG_TRY_VALUE(j.numberOr("duration", b.duration));
  b.curve = ENG_TRY_VALUE(r.curve(j));
  return b;
}

}  // namespace facial
