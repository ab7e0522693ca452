#include "facial/runtime/graph/parameters.h"

namespace facial {

std::string_view parameterTypeName(ParameterType value) { return eng::nameOf(kParameterTypeNames, value); }

std::optional<ParameterType> parameterTypeFromName(std::string_view name) { return eng::valueNamed(kParameterTypeNames, name); }

}  // namespace facial
