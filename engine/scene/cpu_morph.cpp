#include "engine/scene/cpu_morph.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace eng {

void morphPrimitiveCpu(const Primitive& primitive, std::span<const float> meshWeights,
                       std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals) {
  const size_t n = primitive.vertexCount();
  if (meshWeights.size() != primitive.targets.size())
    throw std::invalid_argument("morphPrimitiveCpu: " + std::to_string(meshWeights.size()) + " weights for " +
                                std::to_string(primitive.targets.size()) + " targets");
  if (outPositions.size() != n)
    throw std::invalid_argument("morphPrimitiveCpu: outPositions has " + std::to_string(outPositions.size()) +
                                " entries, primitive has " + std::to_string(n) + " vertices");
  if (!outNormals.empty() && outNormals.size() != n)
    throw std::invalid_argument("morphPrimitiveCpu: outNormals has " + std::to_string(outNormals.size()) +
                                " entries, primitive has " + std::to_string(n) + " vertices");
  const bool doNormals = !outNormals.empty();
  if (doNormals && primitive.normals.size() != n)
    throw std::invalid_argument("morphPrimitiveCpu: primitive has " + std::to_string(primitive.normals.size()) +
                                " normals for " + std::to_string(n) + " vertices");

  std::copy(primitive.positions.begin(), primitive.positions.end(), outPositions.begin());
  if (doNormals) std::copy(primitive.normals.begin(), primitive.normals.end(), outNormals.begin());

  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const float w = meshWeights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = primitive.targets[t];
    if (!target.positions.empty())
      for (size_t v = 0; v < n; ++v) outPositions[v] += w * target.positions[v];
    if (doNormals && !target.normals.empty())
      for (size_t v = 0; v < n; ++v) outNormals[v] += w * target.normals[v];
  }
  if (doNormals) {
    for (glm::vec3& nrm : outNormals) {
      const float len2 = glm::dot(nrm, nrm);
      // A normal blended to (near) zero has no direction; keep it as is rather than make NaNs.
      if (len2 > 1e-20f) nrm *= 1.0f / std::sqrt(len2);
    }
  }
}

}  // namespace eng
