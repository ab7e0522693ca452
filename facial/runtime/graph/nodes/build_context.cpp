#include "facial/runtime/graph/nodes/build_context.h"

#include <cmath>

namespace facial {

eng::Error BuildContext::problem(std::string_view subpath, std::string_view problem) const {
  std::string out = origin;
  if (!subpath.empty()) out += "/" + std::string(subpath);
  return eng::makeError(eng::ErrorKind::Malformed, out + ": " + std::string(problem));
}

eng::Result<void> BuildContext::checkInput(const FloatInput& input, std::string_view field) const {
  if (input.parameter == kNoParameter) {
    if (!std::isfinite(input.constant)) return problem(field, "constant is not finite");
    return {};
  }
  if (input.parameter >= parameters.size())
    return problem(field, "parameter index " + std::to_string(input.parameter) + " out of range (" +
                              std::to_string(parameters.size()) + " parameters)");
  return {};
}

eng::Result<void> BuildContext::checkParameter(ParameterIndex parameter, ParameterType type,
                                               std::string_view field) const {
  if (parameter >= parameters.size())
    return problem(field, "parameter index " + std::to_string(parameter) + " out of range (" +
                              std::to_string(parameters.size()) + " parameters)");
  if (parameters[parameter].type != type)
    return problem(field, "parameter '" + parameters[parameter].name + "' is a " +
                              std::string(parameterTypeName(parameters[parameter].type)) + ", expected a " +
                              std::string(parameterTypeName(type)));
  return {};
}

}  // namespace facial
