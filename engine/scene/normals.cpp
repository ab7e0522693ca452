#include "engine/scene/normals.h"

#include <cmath>

#include "engine/scene/position_hash.h"

namespace eng {

std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  const size_t n = positions.size();
  // Seam copies share one normal.
  const ExactPositionGroups groups = groupExactPositions(positions);
  const std::vector<uint32_t>& group = groups.groupOf;
  const size_t groupCount = groups.firstVertex.size();

  // In double: with coordinates near float's range (1e30 is a valid float)
  // the float cross product and its squared length overflow to inf and the
  // normal to NaN; in double any finite float input gives a finite normal.
  std::vector<glm::dvec3> sums(groupCount, glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;
    // The cross product's length is twice the area: larger faces weigh more.
    const glm::dvec3 pa(positions[a]);
    const glm::dvec3 faceNormal = glm::cross(glm::dvec3(positions[b]) - pa, glm::dvec3(positions[c]) - pa);
    sums[group[a]] += faceNormal;
    sums[group[b]] += faceNormal;
    sums[group[c]] += faceNormal;
  }
  std::vector<glm::vec3> normals(n);
  for (size_t v = 0; v < n; ++v) {
    const glm::dvec3 s = sums[group[v]];
    const double len = glm::length(s);
    normals[v] = std::isfinite(len) && len > 1e-15 ? glm::vec3(s / len) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

}  // namespace eng
