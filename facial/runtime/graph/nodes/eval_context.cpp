#include "facial/runtime/graph/nodes/eval_context.h"

#include <algorithm>

#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/pose_jobs.h"

namespace facial {

void EvalContext::evaluate(NodeIndex node, std::span<float> out) {
  std::visit([&](const auto& n) { n.evaluate(*this, node, out); }, definition.nodes()[node].data);
}

void EvalContext::reset(NodeIndex node) {
  std::visit(
      [&](const auto& n) {
        using T = std::decay_t<decltype(n)>;
        if constexpr (HasNodeState<T>) n.reset(state<typename T::State>(node));
      },
      definition.nodes()[node].data);
  for (NodeIndex child : definition.inputs(node)) reset(child);
}

void EvalContext::evaluateWeightedSum(std::span<const NodeIndex> inputs, std::span<const float> weights,
                                      std::span<float> out) {
  std::fill(out.begin(), out.end(), 0.0f);
  ScratchPose pose(scratch);
  for (size_t i = 0; i < inputs.size(); ++i) {
    if (weights[i] <= 0.0f) continue;
    evaluate(inputs[i], pose.pose());
    AccumulatePoseJob{.input = pose.pose(), .weight = weights[i], .out = out}.Run();
  }
}

}  // namespace facial
