#include "bake/head/tongue.h"

#include <algorithm>

namespace bake {

PartMesh buildTongue(const glm::vec3& seam) {
  const glm::vec3 centre(0.0f, seam.y - 0.0088f, seam.z - 0.036f);
  const glm::vec3 radii(0.0168f, 0.0060f, 0.0225f);
  return sphereGrid(16, 28, [&](const glm::vec3& d) {
    // Flatter on top, with a shallow groove down the middle.
    glm::vec3 p = d * radii;
    if (p.y > 0.0f) p.y *= 0.8f - 0.25f * std::exp(-(d.x * d.x) / 0.02f);
    return centre + p;
  });
}

}  // namespace bake
