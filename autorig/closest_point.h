#pragma once
// Closest points on a triangle soup, through a uniform grid of the triangles'
// bounds, searched in growing shells until no unsearched cell can be closer:
// O(log)-ish per query on a surface, never a scan of every triangle.
// Vertices carry a FaceRegion so a query may refuse one region (an upper-lip
// vertex never lands on the lower lip, nor on a triangle that reaches it).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_frame.h"

namespace autorig {

struct ClosestPoint {
  uint32_t triangle = 0;
  glm::vec3 barycentric{1.0f, 0.0f, 0.0f};
  glm::vec3 position{0.0f};
  float distance = 0.0f;
  bool found = false;
};

class TriangleGrid {
 public:
  // triangles index `positions`; regions: one per position (or empty: all None).
  TriangleGrid(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> triangles,
               std::span<const FaceRegion> regions);

  // The closest point on a triangle not in region `refused` (None refuses
  // nothing; a triangle spanning the lips' meeting line at a mouth corner is
  // neither lip's, one spanning an eye's corner both lids') and, when
  // `facing` is not zero, whose normal is within about 70 degrees of it (the
  // cheek never lands on the inside of the mouth or the back of an ear),
  // within maxDistance; found = false when there is none.
  ClosestPoint closest(const glm::vec3& p, FaceRegion refused, float maxDistance,
                       const glm::vec3& facing = glm::vec3(0.0f)) const;

 private:
  glm::ivec3 cellOf(const glm::vec3& p) const;
  size_t cellIndex(const glm::ivec3& c) const { return (size_t(c.z) * size_t(dims_.y) + size_t(c.y)) * size_t(dims_.x) + size_t(c.x); }

  std::vector<glm::vec3> positions_;
  std::vector<std::array<uint32_t, 3>> triangles_;
  std::vector<uint32_t> regionBits_;  // per triangle, bit r: a corner is in FaceRegion r
  std::vector<glm::vec3> normals_;  // unit, per triangle (zero for a degenerate one)
  glm::vec3 min_{0.0f};
  float cell_ = 1.0f;
  glm::ivec3 dims_{1};
  std::vector<uint32_t> cellStart_;  // CSR: triangles of cell i at cellTriangles_[cellStart_[i] .. cellStart_[i+1])
  std::vector<uint32_t> cellTriangles_;
};

// Area-weighted unit normals of a triangle soup's vertices (zero for a vertex
// on no triangle), turned outwards whichever way the file winds its
// triangles (as the grid's triangle normals are).
std::vector<glm::vec3> vertexNormals(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> triangles);

// The closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision
// Detection 5.1.5), with its barycentric coordinates.
glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            glm::vec3& barycentric);

}  // namespace autorig
