#pragma once
// Reference CPU morphing: the classic per-vertex lerp that rewrites the whole
// vertex buffer, p = base + sum_i w_i * delta_i. Tests check the GPU path
// against it and benchmarks use it as the baseline.
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// A job over spans (ozz style): Validate() names what does not fit; Run()
// validates, then writes the outputs without allocating, or returns false
// and leaves them untouched.
struct MorphPrimitiveJob {
  const Primitive* primitive = nullptr;
  // One finite weight per target of the primitive (its mesh's weights).
  std::span<const float> weights;
  // primitive->vertexCount() long; normals renormalised. outNormals may be
  // empty (positions only); otherwise the primitive needs one normal a vertex.
  std::span<glm::vec3> outPositions;
  std::span<glm::vec3> outNormals;
  Result<void> Validate() const;
  bool Run() const;
};

// MorphPrimitiveJob{&primitive, meshWeights, outPositions, outNormals}.Run():
// false (outputs untouched) when the sizes do not fit or a weight is not finite.
bool morphPrimitiveCpu(const Primitive& primitive, std::span<const float> meshWeights,
                       std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals);

}  // namespace eng
