#include "engine/scene/position_hash.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "engine/core/work_counter.h"

namespace eng {

ExactPosition::ExactPosition(const glm::vec3& p) {
  const glm::vec3 q = p + glm::vec3(0.0f);  // -0.0 + 0.0 is +0.0
  std::memcpy(&x, &q.x, 4);
  std::memcpy(&y, &q.y, 4);
  std::memcpy(&z, &q.z, 4);
}

size_t ExactPosition::Hash::operator()(const ExactPosition& k) const {
  uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
  h ^= (k.y + 0x7F4A7C15ull + (h << 6) + (h >> 2)) * 0xBF58476D1CE4E5B9ull;
  h ^= (k.z + 0x94D049BBull + (h << 6) + (h >> 2)) * 0x94D049BB133111EBull;
  return static_cast<size_t>(h ^ (h >> 31));
}

ExactPositionGroups groupExactPositions(std::span<const glm::vec3> positions) {
  struct Keyed {
    ExactPosition key;
    uint32_t vertex;
  };
  std::vector<Keyed> keyed(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) keyed[v] = {ExactPosition(positions[v]), static_cast<uint32_t>(v)};
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return std::tie(a.key.x, a.key.y, a.key.z, a.vertex) < std::tie(b.key.x, b.key.y, b.key.z, b.vertex);
  });
  // Runs of one key, numbered as sorted, then renumbered by first vertex.
  std::vector<uint32_t> run(positions.size());
  uint32_t runs = 0;
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && !(keyed[i].key == keyed[i - 1].key)) ++runs;
    run[keyed[i].vertex] = runs;
  }
  constexpr uint32_t kUnnumbered = UINT32_MAX;
  std::vector<uint32_t> numberOfRun(keyed.empty() ? 0 : size_t(runs) + 1, kUnnumbered);
  ExactPositionGroups groups;
  groups.groupOf.resize(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    uint32_t& number = numberOfRun[run[v]];
    if (number == kUnnumbered) {
      number = static_cast<uint32_t>(groups.firstVertex.size());
      groups.firstVertex.push_back(static_cast<uint32_t>(v));
    }
    groups.groupOf[v] = number;
  }
  return groups;
}

size_t PositionHash::CellKeyHash::operator()(const CellKey& k) const {
  // Teschner et al.'s spatial hash primes.
  return static_cast<size_t>((static_cast<uint64_t>(static_cast<uint32_t>(k.x)) * 73856093u) ^
                             (static_cast<uint64_t>(static_cast<uint32_t>(k.y)) * 19349663u) ^
                             (static_cast<uint64_t>(static_cast<uint32_t>(k.z)) * 83492791u));
}

PositionHash::CellKey PositionHash::cellOf(const glm::vec3& p) const {
  auto axis = [this](float v) {
    const double c = std::floor(static_cast<double>(v) / cellSize_);
    return static_cast<int32_t>(std::clamp(c, -2.0e9, 2.0e9));
  };
  return {axis(p.x), axis(p.y), axis(p.z)};
}

PositionHash::PositionHash(std::span<const glm::vec3> points, float maxRadius)
    : points_(points), cellSize_(maxRadius > 0.0f ? 2.0f * maxRadius : 2e-6f) {
  std::vector<std::pair<CellKey, uint32_t>> keyed(points.size());
  for (size_t i = 0; i < points.size(); ++i) keyed[i] = {cellOf(points[i]), static_cast<uint32_t>(i)};
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return std::tie(a.first.x, a.first.y, a.first.z, a.second) < std::tie(b.first.x, b.first.y, b.first.z, b.second);
  });
  order_.resize(keyed.size());
  cells_.reserve(keyed.size());
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) {
      order_[j] = keyed[j].second;
      ++j;
    }
    cells_.emplace(keyed[i].first, std::make_pair(static_cast<uint32_t>(i), static_cast<uint32_t>(j)));
    i = j;
  }
}

template <class Visit>
void PositionHash::forEachNearCell(const glm::vec3& p, Visit&& visit) const {
  const CellKey c = cellOf(p);
  // With cells twice the radius, the ball around p reaches at most one
  // neighbour per axis: the one on the side of the nearer cell wall.
  auto side = [this](float v, int32_t cell) {
    return static_cast<double>(v) / cellSize_ - cell < 0.5 ? -1 : 1;
  };
  const int sx = side(p.x, c.x), sy = side(p.y, c.y), sz = side(p.z, c.z);
  for (int dz = 0; dz <= 1; ++dz)
    for (int dy = 0; dy <= 1; ++dy)
      for (int dx = 0; dx <= 1; ++dx) {
        auto it = cells_.find({c.x + dx * sx, c.y + dy * sy, c.z + dz * sz});
        if (it != cells_.end()) visit(std::span<const uint32_t>(order_).subspan(it->second.first, it->second.second - it->second.first));
      }
}

std::vector<uint32_t> PositionHash::near(const glm::vec3& p, float radius) const {
  std::vector<std::pair<float, uint32_t>> found;
  const float r2 = radius * radius;
  forEachNearCell(p, [&](std::span<const uint32_t> cell) {
    countWork(cell.size());
    for (const uint32_t i : cell) {
      const glm::vec3 d = points_[i] - p;
      const float d2 = glm::dot(d, d);
      if (d2 <= r2) found.emplace_back(d2, i);
    }
  });
  std::sort(found.begin(), found.end());
  std::vector<uint32_t> out(found.size());
  for (size_t i = 0; i < found.size(); ++i) out[i] = found[i].second;
  return out;
}

int64_t PositionHash::nearestFree(const glm::vec3& p, float radius, const std::vector<bool>& taken,
                                  size_t maxVisited) const {
  int64_t best = -1;
  float bestD2 = radius * radius;
  size_t visited = 0;
  forEachNearCell(p, [&](std::span<const uint32_t> cell) {
    for (size_t k = 0; k < cell.size() && visited < maxVisited; ++k, ++visited) {
      const uint32_t i = cell[k];
      if (i < taken.size() && taken[i]) continue;
      const glm::vec3 d = points_[i] - p;
      const float d2 = glm::dot(d, d);
      if (d2 < bestD2 || (d2 == bestD2 && (best < 0 || i < best))) best = i, bestD2 = d2;
    }
  });
  countWork(visited);
  return best;
}

}  // namespace eng
