#include "facial/runtime/graph/graph_definition.h"

namespace facial {

std::string_view nodeTypeName(const NodeData& data) {
  return std::visit([](const auto& node) { return std::decay_t<decltype(node)>::kType; }, data);
}

std::optional<ParameterIndex> GraphDefinition::findParameter(std::string_view name) const {
  return parameterIndex_.find(name);
}

std::optional<NodeIndex> GraphDefinition::findNode(std::string_view name) const {
  if (name.empty()) return std::nullopt;
  return nodeIndex_.find(name);
}

}  // namespace facial
