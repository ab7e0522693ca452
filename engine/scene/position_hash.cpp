#include "engine/scene/position_hash.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace eng {

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

PositionHash::PositionHash(std::span<const glm::vec3> points, float cellSize)
    : points_(points), cellSize_(cellSize > 0.0f ? cellSize : 1e-6f) {
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

std::vector<uint32_t> PositionHash::near(const glm::vec3& p, float radius) const {
  std::vector<std::pair<float, uint32_t>> found;
  const CellKey c = cellOf(p);
  const float r2 = radius * radius;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
        if (it == cells_.end()) continue;
        for (uint32_t i = it->second.first; i < it->second.second; ++i) {
          const glm::vec3 d = points_[order_[i]] - p;
          const float d2 = glm::dot(d, d);
          if (d2 <= r2) found.emplace_back(d2, order_[i]);
        }
      }
  std::sort(found.begin(), found.end());
  std::vector<uint32_t> out(found.size());
  for (size_t i = 0; i < found.size(); ++i) out[i] = found[i].second;
  return out;
}

}  // namespace eng
