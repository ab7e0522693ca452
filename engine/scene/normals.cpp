#include "engine/scene/normals.h"

#include <cmath>
#include <cstring>
#include <unordered_map>

namespace eng {
namespace {

struct PositionKey {
  uint32_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (k.y + 0x7F4A7C15ull + (h << 6) + (h >> 2)) * 0xBF58476D1CE4E5B9ull;
    h ^= (k.z + 0x94D049BBull + (h << 6) + (h >> 2)) * 0x94D049BB133111EBull;
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

PositionKey keyOf(const glm::vec3& p) {
  // +0.0 and -0.0 are the same place.
  const glm::vec3 q = p + glm::vec3(0.0f);
  PositionKey k;
  std::memcpy(&k.x, &q.x, 4);
  std::memcpy(&k.y, &q.y, 4);
  std::memcpy(&k.z, &q.z, 4);
  return k;
}

}  // namespace

std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
  const size_t n = positions.size();
  // Group vertices by exact position.
  std::vector<uint32_t> group(n);
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> groups;
  groups.reserve(n);
  for (size_t v = 0; v < n; ++v)
    group[v] = groups.try_emplace(keyOf(positions[v]), static_cast<uint32_t>(groups.size())).first->second;

  // In double: with coordinates near float's range (1e30 is a valid float)
  // the float cross product and its squared length overflow to inf and the
  // normal to NaN; in double any finite float input gives a finite normal.
  std::vector<glm::dvec3> sums(groups.size(), glm::dvec3(0.0));
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
