#pragma once
// Reference CPU morphing: the classic per-vertex lerp that rewrites the whole
// vertex buffer, p = base + sum_i w_i * delta_i. Tests check the GPU path
// against it and benchmarks use it as the baseline.
#include <span>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace eng {

// meshWeights: one weight per target of the primitive (its mesh's weights).
// outPositions/outNormals: primitive.vertexCount() long; normals renormalised
// (left empty-sized when outNormals is empty). Zero weights are skipped.
// Preconditions (checked, throws std::invalid_argument naming the sizes):
// meshWeights.size() == targets.size(), output sizes == vertexCount.
void morphPrimitiveCpu(const Primitive& primitive, std::span<const float> meshWeights,
                       std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals);

}  // namespace eng
