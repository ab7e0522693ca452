#include "engine/vk/draw/active_weights.h"

#include <cmath>
#include <string>

namespace eng::vk {

Result<void> ActiveWeightsJob::Validate() const {
  if (output.size() < weights.size())
    return makeError(ErrorKind::InvalidArgument, "active weights: output has room for " + std::to_string(output.size()) + " entries, " +
                     std::to_string(weights.size()) + " weights given");
  for (size_t i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i]))
      return makeError(ErrorKind::InvalidArgument, "active weights: weight " + std::to_string(i) + " of " + std::to_string(weights.size()) +
                       " is not finite (" + std::to_string(weights[i]) + ")");
  }
  return {};
}

uint32_t ActiveWeightsJob::Run() const {
  uint32_t count = 0;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (std::abs(weights[i]) >= kActiveWeightThreshold) output[count++] = {static_cast<uint32_t>(i), weights[i]};
  }
  return count;
}

}  // namespace eng::vk
