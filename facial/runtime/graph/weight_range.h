#pragma once
// The weights a file or a command line may set (timeline keys, `--weight`,
// `--shape`): a target's weight is 0..1 by convention, and exaggeration or a
// corrective negative goes a few times past that. Nothing real comes near
// 1e38, which overflows to infinity once scaled or summed. (A graph's pose
// weights are held to [0, 1] by the pose node itself.)
#include <string>
#include <string_view>

#include "engine/core/result.h"

namespace facial {

inline constexpr float kMaxWeightMagnitude = 10.0f;

constexpr bool isWeightInRange(float weight) { return weight >= -kMaxWeightMagnitude && weight <= kMaxWeightMagnitude; }

// "weight 1e+38 is outside [-10, 10]"
std::string weightRangeProblem(float weight);

struct NamedWeight {
  std::string name;
  float value = 0.0f;
};

// "NAME=VALUE" (the last '=' splits) with VALUE a finite number in range;
// `option` ("--weight") names the argument in the error.
eng::Result<NamedWeight> parseNamedWeight(std::string_view assignment, std::string_view option);

}  // namespace facial
