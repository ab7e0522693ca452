#include "facial/runtime/graph/nodes/additive_node.h"

#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/graph/pose_jobs.h"

namespace facial {

float RegionMask::weight(const ChannelInfo& channel) const {
  if (region && channel.region != region) return 0.0f;
  if (side && channel.side != *side) return 0.0f;
  return 1.0f;
}

eng::Result<void> AdditiveNode::prepare(const BuildContext& ctx) {
  maskWeights.resize(ctx.channels.size());
  for (uint32_t c = 0; c < ctx.channels.size(); ++c) maskWeights[c] = mask.weight(ctx.channels[c]);
  return ctx.checkInput(weight, "weight");
}

void AdditiveNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  ctx.evaluate(base, out);
  ScratchPose added(ctx.scratch);
  ctx.evaluate(layer, added.pose());
  AdditivePoseJob{.base = out, .layer = added.pose(), .mask = maskWeights, .weight = ctx.read(weight), .out = out}
      .Run();
}

}  // namespace facial
