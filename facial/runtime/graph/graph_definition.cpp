#include "facial/runtime/graph/graph_definition.h"

namespace facial {

std::string_view nodeTypeName(const NodeData& data) {
  static constexpr std::string_view kNames[] = {"pose",        "blend",    "bilinear",     "controlMap", "freeformMap",
                                                "additive",    "timeline", "stateMachine", "blink"};
  static_assert(std::size(kNames) == std::variant_size_v<NodeData>);
  return kNames[data.index()];
}

std::optional<ParameterIndex> GraphDefinition::findParameter(std::string_view name) const {
  for (ParameterIndex i = 0; i < parameters_.size(); ++i)
    if (parameters_[i].name == name) return i;
  return std::nullopt;
}

std::optional<NodeIndex> GraphDefinition::findNode(std::string_view name) const {
  if (name.empty()) return std::nullopt;
  for (NodeIndex i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].name == name) return i;
  return std::nullopt;
}

}  // namespace facial
