#include "bake/head/part_mesh.h"

#include <cmath>
#include <numbers>

#include "bake/head/surface_normals.h"

namespace bake {

uint32_t PartMesh::addVertex(const glm::vec3& p, const glm::vec2& uv, uint32_t weldId) {
  const uint32_t v = static_cast<uint32_t>(positions.size());
  positions.push_back(p);
  uvs.push_back(uv);
  weldIds.push_back(weldId == UINT32_MAX ? v : weldId);
  return v;
}

void PartMesh::computeNormals() { normals = weldedNormals(positions, indices, weldIds); }

void PartMesh::append(const PartMesh& other) {
  const uint32_t base = static_cast<uint32_t>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  uvs.insert(uvs.end(), other.uvs.begin(), other.uvs.end());
  for (uint32_t w : other.weldIds) weldIds.push_back(w + base);
  for (uint32_t i : other.indices) indices.push_back(i + base);
}

PartMesh sphereGrid(int rings, int segments, const std::function<glm::vec3(const glm::vec3&)>& shape) {
  PartMesh m;
  const uint32_t front = m.addVertex(shape(glm::vec3(0, 0, 1)), glm::vec2(0.5f, 0.0f), UINT32_MAX);
  std::vector<uint32_t> grid;
  for (int j = 1; j < rings; ++j) {
    const float theta = std::numbers::pi_v<float> * j / rings;
    uint32_t first = 0;
    for (int i = 0; i <= segments; ++i) {
      const float phi = 2.0f * std::numbers::pi_v<float> * (i % segments) / segments;
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const uint32_t v =
          m.addVertex(shape(d), glm::vec2(float(i) / segments, float(j) / rings), i == segments ? first : UINT32_MAX);
      if (i == 0) first = v;
      grid.push_back(v);
    }
  }
  const uint32_t back = m.addVertex(shape(glm::vec3(0, 0, -1)), glm::vec2(0.5f, 1.0f), UINT32_MAX);
  auto at = [&](int j, int i) -> uint32_t {
    if (j == 0) return front;
    if (j == rings) return back;
    return grid[size_t(j - 1) * (segments + 1) + i];
  };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = at(j, i), b = at(j + 1, i), c = at(j + 1, i + 1), d = at(j, i + 1);
      if (j == 0) {
        m.indices.insert(m.indices.end(), {a, b, c});
      } else if (j == rings - 1) {
        m.indices.insert(m.indices.end(), {a, b, d});
      } else {
        m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
      }
    }
  m.computeNormals();
  return m;
}

}  // namespace bake
