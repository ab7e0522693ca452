#include "facial/runtime/graph/parameters.h"

namespace facial {

std::string_view toString(ParameterType type) {
  switch (type) {
    case ParameterType::Float: return "float";
    case ParameterType::Bool: return "bool";
    case ParameterType::Trigger: return "trigger";
  }
  return "float";
}

std::optional<ParameterType> parameterTypeFromString(std::string_view name) {
  for (ParameterType t : {ParameterType::Float, ParameterType::Bool, ParameterType::Trigger})
    if (toString(t) == name) return t;
  return std::nullopt;
}

}  // namespace facial
