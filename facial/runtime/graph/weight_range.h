#pragma once
// The weights a file or a command line may set (timeline keys, graph poses and
// preset intensities, `--weight`): a target's weight is 0..1 by convention, and
// exaggeration or a corrective negative goes a few times past that. Nothing
// real comes near 1e38, which overflows to infinity once scaled or summed.
#include <cstdio>
#include <string>

namespace facial {

inline constexpr float kMaxWeightMagnitude = 10.0f;

constexpr bool isWeightInRange(float weight) { return weight >= -kMaxWeightMagnitude && weight <= kMaxWeightMagnitude; }

// "weight 1e+38 is outside [-10, 10]"
inline std::string weightRangeProblem(float weight) {
  char text[96];
  std::snprintf(text, sizeof text, "weight %g is outside [-%g, %g]", double(weight), double(kMaxWeightMagnitude),
                double(kMaxWeightMagnitude));
  return text;
}

}  // namespace facial
