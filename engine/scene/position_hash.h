#pragma once
// A uniform-grid spatial hash over a fixed point set: "which points lie
// within r of p" in O(1) expected time, so matching two 100k-vertex meshes
// by position stays linear instead of O(n^2).
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

// A position as a hash key, for grouping vertices at exactly one place: the
// copies an exporter splits a vertex into along a UV seam or a hard edge sit
// at bit-identical positions. +0.0 and -0.0 are one place.
struct ExactPosition {
  uint32_t x = 0, y = 0, z = 0;
  ExactPosition() = default;
  explicit ExactPosition(const glm::vec3& p);
  bool operator==(const ExactPosition&) const = default;
  struct Hash {
    size_t operator()(const ExactPosition& k) const;
  };
};

// Vertices at exactly one place as groups, numbered in the order of their
// first vertex (the lowest-numbered). By sorting the positions' bits: a hash
// map allocated a node per vertex, and an autorig transfer groups the
// vertices of every target it makes (under AddressSanitizer those
// allocations were most of a transfer's normals).
struct ExactPositionGroups {
  std::vector<uint32_t> groupOf;      // per vertex
  std::vector<uint32_t> firstVertex;  // per group
};
ExactPositionGroups groupExactPositions(std::span<const glm::vec3> positions);

class PositionHash {
 public:
  // Queries up to maxRadius look at the 8 cells of side 2 * maxRadius around p.
  PositionHash(std::span<const glm::vec3> points, float maxRadius);

  // Indices of points within `radius` of p (radius <= maxRadius), nearest
  // first. Looks at every point of the cells around p (counted as work,
  // work_counter.h): a pile of coincident points costs its size per query.
  std::vector<uint32_t> near(const glm::vec3& p, float radius) const;

  // The nearest point within `radius` of p that is not taken[i], looking at
  // no more than maxVisited points; -1 when none. The bound keeps a cluster
  // of coincident points from costing its size per query (n^2 in all):
  // past it, a point is ambiguous anyway. Counts the points looked at
  // (work_counter.h).
  int64_t nearestFree(const glm::vec3& p, float radius, const std::vector<bool>& taken, size_t maxVisited) const;

 private:
  struct CellKey {
    int32_t x, y, z;
    bool operator==(const CellKey&) const = default;
  };
  struct CellKeyHash {
    size_t operator()(const CellKey& k) const;
  };
  CellKey cellOf(const glm::vec3& p) const;
  // The (up to 8) cells a ball of radius <= maxRadius around p can reach.
  template <class Visit>
  void forEachNearCell(const glm::vec3& p, Visit&& visit) const;

  std::span<const glm::vec3> points_;
  float cellSize_;
  std::vector<uint32_t> order_;  // point indices grouped by cell
  std::unordered_map<CellKey, std::pair<uint32_t, uint32_t>, CellKeyHash> cells_;  // [begin, end) into order_
};

}  // namespace eng
