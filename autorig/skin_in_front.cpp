#include "autorig/skin_in_front.h"

#include "engine/scene/ray_triangle.h"

namespace autorig {

SkinInFront::SkinInFront(const LandmarkFrame& frame, float cell)
    : side_(frame.side()), up_(frame.up()), forward_(frame.forward()), cell_(cell) {}

void SkinInFront::add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const uint32_t t = uint32_t(corners_.size() / 3);
  corners_.insert(corners_.end(), {a, b, c});
  const glm::vec2 pa = plane(a), pb = plane(b), pc = plane(c);
  const glm::ivec2 lo = cellOf(glm::min(pa, glm::min(pb, pc))), hi = cellOf(glm::max(pa, glm::max(pb, pc)));
  for (int x = lo.x; x <= hi.x; ++x)
    for (int y = lo.y; y <= hi.y; ++y) cells_[key({x, y})].push_back(t);
}

bool SkinInFront::covers(const glm::vec3& p) const {
  const auto found = cells_.find(key(cellOf(plane(p))));
  if (found == cells_.end()) return false;
  for (uint32_t t : found->second)
    if (eng::intersectRayTriangle(p, forward_, corners_[t * 3], corners_[t * 3 + 1], corners_[t * 3 + 2])) return true;
  return false;
}

}  // namespace autorig
