#pragma once
// A small closed mesh of the built-in head (eyeball, tooth row, tongue, ear)
// and the latitude/longitude grid most of them start from.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace bake {

struct PartMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> weldIds;  // see surface_normals.h

  uint32_t addVertex(const glm::vec3& p, const glm::vec2& uv, uint32_t weldId);
  void computeNormals();
  // Appends `other` (indices shifted), keeping both closed.
  void append(const PartMesh& other);
};

// Closed grid over the unit sphere with poles on +Z (ring 0) and -Z: vertex
// position = shape(unit direction); uv = (azimuth / 2pi, polar angle / pi).
PartMesh sphereGrid(int rings, int segments, const std::function<glm::vec3(const glm::vec3&)>& shape);

}  // namespace bake
