#include "facial/runtime/graph/nodes/blend_node.h"

#include <algorithm>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/graph/pose_jobs.h"

namespace facial {

using detail::NodeReader;

eng::Result<void> BlendNode::prepare(const BuildContext& ctx) { return ctx.checkInput(factor, "factor"); }

void BlendNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  ctx.evaluate(a, out);
  ScratchPose p1(ctx.scratch);
  ctx.evaluate(b, p1.pose());
  const float t = curve(std::clamp(ctx.read(factor), 0.0f, 1.0f));
  LerpPoseJob{.a = out, .b = p1.pose(), .t = t, .out = out}.Run();
}

eng::Result<BlendNode> BlendNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "a", "b", "factor", "curve"}));
  BlendNode b{.a = ENG_TRY_VALUE(r.nodeAt(j, "a")), .b = ENG_TRY_VALUE(r.nodeAt(j, "b"))};
  b.factor = ENG_TRY_VALUE(r.floatInput(j, "factor", 0.0f));
  b.curve = ENG_TRY_VALUE(r.curve(j));
  return b;
}

}  // namespace facial
