#include "engine/scene/normals.h"

#include <algorithm>
#include <cmath>

#include "engine/scene/position_hash.h"

namespace eng {
namespace {

// Each vertex's group of vertices at exactly its position, numbered from 0;
// `count` receives the number of groups. By sorting the positions' bits: a
// hash map allocated a node per vertex, and an autorig transfer computes the
// normals of every target it makes (under AddressSanitizer those allocations
// were most of a transfer's normals).
std::vector<uint32_t> exactPositionGroups(std::span<const glm::vec3> positions, size_t& count) {
  struct Keyed {
    ExactPosition key;
    uint32_t vertex;
  };
  std::vector<Keyed> keyed(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) keyed[v] = {ExactPosition(positions[v]), static_cast<uint32_t>(v)};
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    if (a.key.x != b.key.x) return a.key.x < b.key.x;
    return a.key.y != b.key.y ? a.key.y < b.key.y : a.key.z < b.key.z;
  });
  std::vector<uint32_t> group(positions.size());
  count = 0;
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && !(keyed[i].key == keyed[i - 1].key)) ++count;
    group[keyed[i].vertex] = static_cast<uint32_t>(count);
  }
  if (!keyed.empty()) ++count;
  return group;
}

}  // namespace

std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  const size_t n = positions.size();
  size_t groupCount = 0;
  const std::vector<uint32_t> group = exactPositionGroups(positions, groupCount);

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
