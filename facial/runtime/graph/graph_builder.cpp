#include "facial/runtime/graph/graph_builder.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/graph_instance.h"
#include "facial/runtime/graph/nodes/build_context.h"

namespace facial {

GraphBuilder::GraphBuilder(ChannelSet channels, size_t maxBytes) : budget_(maxBytes) {
  definition_.channels_ = std::move(channels);
}

ParameterIndex GraphBuilder::addParameter(std::string name, ParameterType type, float defaultValue) {
  definition_.parameterIndex_.add(name, static_cast<ParameterIndex>(definition_.parameters_.size()));
  definition_.parameters_.push_back({std::move(name), type, type == ParameterType::Trigger ? 0.0f : defaultValue});
  return static_cast<ParameterIndex>(definition_.parameters_.size() - 1);
}

ParameterIndex GraphBuilder::addFloat(std::string name, float defaultValue) {
  return addParameter(std::move(name), ParameterType::Float, defaultValue);
}

ParameterIndex GraphBuilder::addBool(std::string name, bool defaultValue) {
  return addParameter(std::move(name), ParameterType::Bool, defaultValue ? 1.0f : 0.0f);
}

ParameterIndex GraphBuilder::addTrigger(std::string name) { return addParameter(std::move(name), ParameterType::Trigger); }

std::optional<ParameterIndex> GraphBuilder::findParameter(std::string_view name) const {
  return definition_.findParameter(name);
}

uint32_t GraphBuilder::addTimeline(Timeline timeline) {
  definition_.timelineIndex_.add(timeline.name, static_cast<uint32_t>(definition_.timelines_.size()));
  definition_.timelines_.push_back(std::move(timeline));
  return static_cast<uint32_t>(definition_.timelines_.size() - 1);
}

std::optional<uint32_t> GraphBuilder::findTimeline(std::string_view name) const {
  return definition_.timelineIndex_.find(name);
}

NodeIndex GraphBuilder::add(NodeData node, std::string name, std::string origin) {
  if (overBudget_) return kNoNode;
  const NodeIndex index = static_cast<NodeIndex>(definition_.nodes_.size());
  if (origin.empty()) origin = "node " + std::to_string(index) + " (" + std::string(nodeTypeName(node)) + ")";
  // A pose holds its weights; an additive node makes its mask's at build.
  const size_t channels = definition_.channels_.size();
  const size_t dense = std::holds_alternative<PoseNode>(node)       ? std::get<PoseNode>(node).weights.size()
                       : std::holds_alternative<AdditiveNode>(node) ? channels
                                                                      : 0;
  const size_t bytes = sizeof(NodeDef) + name.size() + origin.size() + dense * sizeof(float) +
                       GraphInstance::nodeStateBytes(node, definition_.poseStride());
  if (auto ok = budget_.charge(bytes, "node " + std::to_string(index) + " (" + std::to_string(channels) + " channels)");
      !ok) {
    overBudget_ = ok.error().prefixed(origin + ": ");
    return kNoNode;
  }
  if (!name.empty()) definition_.nodeIndex_.add(name, index);
  definition_.nodes_.push_back({std::move(name), std::move(origin), std::move(node)});
  return index;
}

namespace {

// Scratch poses the subtree at `node` needs: its own temporaries, held while
// its children evaluate one after another, plus the hungriest child.
uint32_t scratchNeed(const GraphDefinition& graph, NodeIndex node) {
  uint32_t deepest = 0;
  for (NodeIndex child : graph.inputs(node)) deepest = std::max(deepest, scratchNeed(graph, child));
  const uint32_t own = std::visit([](const auto& n) { return std::decay_t<decltype(n)>::kScratchPoses; },
                                  graph.nodes()[node].data);
  return own + deepest;
}

}  // namespace

eng::Result<SharedGraphDefinition> GraphBuilder::build() const {
  if (overBudget_) return *overBudget_;
  auto graph = std::make_shared<GraphDefinition>(definition_);
  if (graph->channels_.empty()) return eng::makeError(eng::ErrorKind::Malformed, "graph has no channels");

  const std::vector<ParameterDecl>& params = graph->parameters_;
  for (size_t i = 0; i < params.size(); ++i) {
    const std::string where = "/parameters/" + std::to_string(i);
    if (params[i].name.empty()) return eng::makeError(eng::ErrorKind::Malformed, where + ": empty parameter name");
    if (graph->findParameter(params[i].name) != i)
      return eng::makeError(eng::ErrorKind::Malformed, where + ": parameter '" + params[i].name + "' is declared twice");
    if (!std::isfinite(params[i].defaultValue))
      return eng::makeError(eng::ErrorKind::Malformed, where + ": default of '" + params[i].name + "' is not finite");
    if (params[i].type == ParameterType::Bool && params[i].defaultValue != 0.0f && params[i].defaultValue != 1.0f)
      return eng::makeError(eng::ErrorKind::Malformed, where + ": bool '" + params[i].name + "' default must be 0 or 1");
  }
  for (size_t i = 0; i < graph->timelines_.size(); ++i)
    if (auto valid = graph->timelines_[i].validate(); !valid)
      return valid.error().prefixed("timeline '" + graph->timelines_[i].name + "': ");

  // Wiring: a tree rooted at root_, every node used exactly once.
  const uint32_t count = static_cast<uint32_t>(graph->nodes_.size());
  if (graph->root_ >= count)
    return eng::makeError(eng::ErrorKind::Malformed, count == 0 ? std::string("graph has no nodes")
                                     : "root node " + std::to_string(graph->root_) + " out of range (" +
                                           std::to_string(count) + " nodes)");
  graph->inputs_.clear();
  graph->inputOffsets_.assign(1, 0);
  std::vector<NodeIndex> parent(count, kNoNode);
  std::vector<NodeIndex> inputs;
  for (NodeIndex n = 0; n < count; ++n) {
    const NodeDef& node = graph->nodes_[n];
    inputs.clear();
    std::visit([&](const auto& data) { data.inputs(inputs); }, node.data);
    for (NodeIndex child : inputs) {
      if (child >= count)
        return eng::makeError(eng::ErrorKind::Malformed, node.origin + ": input " +
                              (child == kNoNode ? std::string("not set") : "node " + std::to_string(child)) +
                              " (the graph has " + std::to_string(count) + " nodes)");
      if (child == graph->root_) return eng::makeError(eng::ErrorKind::Malformed, node.origin + ": uses the root node as an input");
      if (parent[child] != kNoNode)
        return eng::makeError(eng::ErrorKind::Malformed, node.origin + ": uses " + graph->nodes_[child].origin + ", which " +
                              graph->nodes_[parent[child]].origin +
                              " already uses (nodes form a tree; add a second node for a second use)");
      parent[child] = n;
    }
    graph->inputs_.insert(graph->inputs_.end(), inputs.begin(), inputs.end());
    graph->inputOffsets_.push_back(static_cast<uint32_t>(graph->inputs_.size()));
  }
  for (NodeIndex n = 0; n < count; ++n) {
    // With one parent each and the root parentless, a node that does not reach
    // the root by parents sits on a cycle or an island.
    NodeIndex at = n;
    for (uint32_t steps = 0; at != graph->root_ && at != kNoNode && steps <= count; ++steps) at = parent[at];
    if (at != graph->root_)
      return eng::makeError(eng::ErrorKind::Malformed, graph->nodes_[n].origin + ": not reachable from the root (unused node or a cycle)");
  }

  for (NodeIndex n = 0; n < count; ++n) {
    NodeDef& node = graph->nodes_[n];
    const BuildContext ctx{graph->channels_, graph->parameters_, graph->timelines_, node.origin};
    if (auto prepared = std::visit([&](auto& data) { return data.prepare(ctx); }, node.data); !prepared)
      return prepared.error();
  }
  for (NodeIndex n = 0; n < count; ++n)
    if (!graph->nodes_[n].name.empty() && graph->findNode(graph->nodes_[n].name) != n)
      return eng::makeError(eng::ErrorKind::Malformed, graph->nodes_[n].origin + ": node name '" + graph->nodes_[n].name + "' is used twice");

  graph->scratchPoseCount_ = scratchNeed(*graph, graph->root_);
  return SharedGraphDefinition(std::move(graph));
}

}  // namespace facial
