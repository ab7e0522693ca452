#pragma once
// The per-frame morph upload: one mesh's weights compacted to the list of
// (target, weight) pairs that actually move vertices. Zero weights cost
// nothing on the GPU because they never reach the vertex shader's loop.
#include <cstdint>
#include <span>

#include "engine/core/result.h"
#include "engine/vk/draw/gpu_types.h"

namespace eng::vk {

// Weights with |w| below this are skipped (they move no vertex visibly).
inline constexpr float kActiveWeightThreshold = 1e-6f;

struct ActiveWeightsJob {
  std::span<const float> weights;  // one per target of the mesh
  std::span<ActiveWeight> output;  // room for weights.size() entries

  // output large enough; every weight finite (the message names the first bad one).
  Result<void> Validate() const;
  // Writes the active pairs in target order; returns how many were written.
  uint32_t Run() const;
};

}  // namespace eng::vk
