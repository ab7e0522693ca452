#include "facial/runtime/graph/graph_definition.h"

namespace facial {

std::string_view nodeTypeName(const NodeData& data) {
  return std::visit([](const auto& node) { return std::decay_t<decltype(node)>::kType; }, data);
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
