#pragma once
// The skin of a face, its triangles binned by where they fall on the face's
// plane (side, up), so a ray straight out of the face tests only its cell's
// few triangles, not every triangle of a dense scan: what the skin hides
// (the carried mouth tucked behind the lips, an eye's rim under its lids).
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_frame.h"

namespace autorig {

class SkinInFront {
 public:
  // `cell`: the bins' side (world units); a few triangles' widths.
  SkinInFront(const LandmarkFrame& frame, float cell);

  void add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
  // Whether a ray from p straight out of the face meets the skin.
  bool covers(const glm::vec3& p) const;

 private:
  glm::vec2 plane(const glm::vec3& p) const { return {glm::dot(p, side_), glm::dot(p, up_)}; }
  glm::ivec2 cellOf(const glm::vec2& q) const { return glm::ivec2(glm::floor(q / cell_)); }
  static int64_t key(const glm::ivec2& c) { return (int64_t(c.x) << 32) ^ int64_t(uint32_t(c.y)); }

  glm::vec3 side_, up_, forward_;
  float cell_;
  std::vector<glm::vec3> corners_;  // three per triangle, world space
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

}  // namespace autorig
