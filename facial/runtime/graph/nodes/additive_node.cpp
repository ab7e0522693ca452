#include "facial/runtime/graph/nodes/additive_node.h"

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/graph/pose_jobs.h"

namespace facial {

using detail::NodeReader;

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

eng::Result<AdditiveNode> AdditiveNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "base", "layer", "weight", "mask"}));
  AdditiveNode a{.base = ENG_TRY_VALUE(r.nodeAt(j, "base")), .layer = ENG_TRY_VALUE(r.nodeAt(j, "layer"))};
  a.weight = ENG_TRY_VALUE(r.floatInput(j, "weight", 1.0f));
  if (auto mask = j.find("mask")) {
    ENG_TRY(mask->allowOnly({"region", "side"}));
    const std::string region = ENG_TRY_VALUE(mask->stringOr("region", "any"));
    if (region == "upper") a.mask.region = FaceRegion::Upper;
    else if (region == "lower") a.mask.region = FaceRegion::Lower;
    else if (region != "any") return ENG_TRY_VALUE(mask->at("region")).error("unknown region (expected any, upper or lower)");
    const std::string side = ENG_TRY_VALUE(mask->stringOr("side", "any"));
    if (side == "left") a.mask.side = FaceSide::Left;
    else if (side == "right") a.mask.side = FaceSide::Right;
    else if (side == "both") a.mask.side = FaceSide::Both;
    else if (side != "any") return ENG_TRY_VALUE(mask->at("side")).error("unknown side (expected any, left, right or both)");
  }
  return a;
}

}  // namespace facial
