#pragma once
// Where a ray meets a triangle (Möller-Trumbore), either face: the one
// intersection test of the face tools (landmark casting, picking in the
// editor, what hides the inside of a mouth).
#include <cmath>
#include <optional>

#include <glm/glm.hpp>

namespace eng {

struct RayTriangleHit {
  float distance = 0.0f;  // along the ray, in units of its direction's length
  float u = 0.0f, v = 0.0f;  // the hit is a + u (b - a) + v (c - a)
};

// Hits in front of the origin only. `slack` widens the barycentric bounds: a
// ray over an edge that two triangles share must not fall through both by rounding.
inline std::optional<RayTriangleHit> intersectRayTriangle(const glm::vec3& origin, const glm::vec3& direction,
                                                          const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                                          float slack = 0.0f) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  const glm::vec3 p = glm::cross(direction, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-20f) return std::nullopt;
  const float inv = 1.0f / det;
  const glm::vec3 s = origin - a;
  const float u = glm::dot(s, p) * inv;
  if (u < -slack || u > 1.0f + slack) return std::nullopt;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(direction, q) * inv;
  if (v < -slack || u + v > 1.0f + slack) return std::nullopt;
  const float t = glm::dot(e2, q) * inv;
  if (t <= 0.0f) return std::nullopt;
  return RayTriangleHit{t, u, v};
}

}  // namespace eng
