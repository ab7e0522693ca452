#include "bake/head/surface_normals.h"

#include <cmath>

namespace bake {

std::vector<glm::vec3> weldedNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                     std::span<const uint32_t> weldIds) {
  std::vector<glm::vec3> sums(positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    // Length is twice the area: larger faces weigh more.
    const glm::vec3 face = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    sums[weldIds[a]] += face;
    sums[weldIds[b]] += face;
    sums[weldIds[c]] += face;
  }
  std::vector<glm::vec3> normals(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    const glm::vec3 s = sums[weldIds[v]];
    const float len2 = glm::dot(s, s);
    normals[v] = len2 > 1e-30f ? s / std::sqrt(len2) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

}  // namespace bake
