#include "facial/runtime/graph/graph_instance.h"

#include <cmath>
#include <type_traits>

namespace facial {
eng::Result<GraphInstance> GraphInstance::create(SharedGraphDefinition definition, uint64_t seed) {
  if (!definition) return eng::makeError(eng::ErrorKind::InvalidArgument, "GraphInstance::create: no graph definition");
  GraphInstance instance;
  instance.definition_ = std::move(definition);
  instance.seed_ = seed;
  const GraphDefinition& graph = *instance.definition_;
  instance.scratch_ = ScratchStack(graph.scratchPoseCount(), graph.poseStride());
  instance.output_.assign(graph.poseStride(), 0.0f);
  instance.states_.resize(graph.nodes().size());
  instance.reset();
  return instance;
}

size_t GraphInstance::nodeStateBytes(const NodeData& node, uint32_t poseStride) {
  const size_t pose = size_t{poseStride} * sizeof(float);
  const size_t held = std::visit(
      [&](const auto& n) -> size_t {
        using T = std::decay_t<decltype(n)>;
        if constexpr (std::is_same_v<T, BilinearNode> || std::is_same_v<T, StateMachineNode>) return 2 * pose;
        else if constexpr (std::is_same_v<T, TimelineNode>) return pose;  // a cursor per track, a track per channel at most
        else return 0;
      },
      node);
  return sizeof(NodeState) + held;
}

size_t GraphInstance::bytesFor(const GraphDefinition& graph) {
  size_t bytes = sizeof(GraphInstance) + graph.parameters().size() * sizeof(float) +
                 (size_t{graph.scratchPoseCount()} + 1) * graph.poseStride() * sizeof(float);
  for (const NodeDef& node : graph.nodes()) bytes += nodeStateBytes(node.data, graph.poseStride());
  return bytes;
}

void GraphInstance::reset() {
  const GraphDefinition& graph = *definition_;
  parameters_.resize(graph.parameters().size());
  for (size_t i = 0; i < parameters_.size(); ++i) parameters_[i] = graph.parameters()[i].defaultValue;
  for (NodeIndex n = 0; n < graph.nodes().size(); ++n)
    std::visit(
        [&](const auto& node) {
          using T = std::decay_t<decltype(node)>;
          if constexpr (HasNodeState<T>) states_[n] = node.makeState(graph, n, seed_);
          else states_[n] = std::monostate{};
        },
        graph.nodes()[n].data);
  std::fill(output_.begin(), output_.end(), 0.0f);
}

bool GraphInstance::update(float dt) {
  if (!std::isfinite(dt) || dt < 0.0f) return false;
  EvalContext ctx{*definition_, parameters_, states_, scratch_, dt};
  ctx.speech = {.track = speechTrack_, .time = speechTime_, .cursors = speechCursors_};
  ctx.evaluate(definition_->root(), output_);
  // Weights leave in [0,1] whatever curves overshoot; NaN (never expected) reads 0.
  for (float& w : std::span<float>(output_).first(definition_->channelCount())) w = w > 0.0f ? (w < 1.0f ? w : 1.0f) : 0.0f;
  return true;
}

bool GraphInstance::setSpeech(const VisemeTrack* track, float audioTime) {
  if (!std::isfinite(audioTime)) return false;
  speechTrack_ = track;
  speechTime_ = audioTime;
  return true;
}

bool GraphInstance::setChecked(ParameterIndex parameter, ParameterType type, float value) {
  if (parameter >= parameters_.size() || definition_->parameters()[parameter].type != type || !std::isfinite(value))
    return false;
  parameters_[parameter] = value;
  return true;
}

bool GraphInstance::setFloat(ParameterIndex parameter, float value) {
  return setChecked(parameter, ParameterType::Float, value);
}

bool GraphInstance::setBool(ParameterIndex parameter, bool value) {
  return setChecked(parameter, ParameterType::Bool, value ? 1.0f : 0.0f);
}

bool GraphInstance::setTrigger(ParameterIndex parameter) { return setChecked(parameter, ParameterType::Trigger, 1.0f); }

bool GraphInstance::resetTrigger(ParameterIndex parameter) {
  return setChecked(parameter, ParameterType::Trigger, 0.0f);
}

std::optional<StateMachineStatus> GraphInstance::stateMachineStatus(NodeIndex node) const {
  const StateMachineNode* machine = definition_->nodeAs<StateMachineNode>(node);
  if (!machine) return std::nullopt;
  return machine->status(*std::get_if<StateMachineNode::State>(&states_[node]));
}

}  // namespace facial
