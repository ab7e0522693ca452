#include "facial/runtime/graph/weight_range.h"

#include <charconv>
#include <cmath>

#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

std::string weightRangeProblem(float weight) {
  return "weight " + formatNumber(weight) + " is outside [-" + formatNumber(kMaxWeightMagnitude) + ", " +
         formatNumber(kMaxWeightMagnitude) + "]";
}

eng::Result<NamedWeight> parseNamedWeight(std::string_view assignment, std::string_view option) {
  const std::string quoted = std::string(option) + " '" + std::string(assignment) + "'";
  const size_t eq = assignment.rfind('=');
  float value = 0.0f;
  const std::string_view number = eq == std::string_view::npos ? std::string_view() : assignment.substr(eq + 1);
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (eq == std::string_view::npos || eq == 0 || number.empty() || ec != std::errc() || end != number.data() + number.size() ||
      !std::isfinite(value))
    return eng::makeError(eng::ErrorKind::InvalidArgument, quoted + " is not NAME=VALUE with a finite number");
  if (!isWeightInRange(value)) return eng::makeError(eng::ErrorKind::InvalidArgument, quoted + ": " + weightRangeProblem(value));
  return NamedWeight{std::string(assignment.substr(0, eq)), value};
}

}  // namespace facial
