#include "bake/head/ear.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace bake {
namespace {

float bump(float x, float centre, float width) {
  const float u = (x - centre) / width;
  return std::exp(-u * u);
}

}  // namespace

PartMesh buildEar(float side) {
  // Frame: `out` faces away from the head (a little forward so the back edge
  // stands off the skull), `up` leans back, `fwd` completes it.
  const glm::vec3 out = glm::normalize(glm::vec3(side, 0.0f, 0.32f));
  const glm::vec3 up = glm::normalize(glm::vec3(0.0f, 1.0f, -0.22f) - out * glm::dot(out, glm::vec3(0.0f, 1.0f, -0.22f)));
  const glm::vec3 fwd = glm::cross(out, up) * side;
  const glm::vec3 centre(side * 0.0735f, 0.002f, -0.012f);
  const float halfHeight = 0.0285f, halfWidth = 0.0165f;
  const float thickness = 0.0052f;  // outer side at the rim

  PartMesh ear = sphereGrid(28, 56, [&](const glm::vec3& d) {
    // d.z is the out axis; (d.x, d.y) the ear plane (x up, y forward).
    const float u = d.x, v = d.y;
    const float rho = std::min(1.0f, std::sqrt(u * u + v * v));
    const float width = halfWidth * (1.0f + 0.22f * u);  // egg shape: wider at the top
    const float edge = std::sqrt(std::max(0.0f, 1.0f - rho * rho));
    float lift;
    if (d.z >= 0.0f) {
      // Rim rolled outward, a bowl off-centre toward the front and bottom,
      // a softer ridge (antihelix) between them, a fleshy lobe below.
      const float rim = bump(rho, 0.86f, 0.12f);
      const float bowl = std::exp(-((u + 0.12f) * (u + 0.12f) + (v - 0.18f) * (v - 0.18f)) / 0.10f);
      const float ridge = bump(rho, 0.58f, 0.10f) * glm::smoothstep(-0.3f, 0.2f, u);
      const float lobe = glm::smoothstep(-0.55f, -0.95f, u) * 0.6f;
      lift = thickness * (0.35f * std::pow(edge, 0.5f) + 0.75f * rim + 0.35f * ridge + lobe - 0.55f * bowl);
      lift = std::max(lift, 0.0006f * std::pow(edge, 0.5f));
    } else {
      lift = -0.0035f * std::pow(edge, 0.7f);
    }
    return centre + up * (u * halfHeight) + fwd * (v * width) + out * lift;
  });
  if (side < 0.0f) {
    // The frame is mirrored for the right ear: flip the winding back outward.
    for (size_t t = 0; t + 2 < ear.indices.size(); t += 3) std::swap(ear.indices[t + 1], ear.indices[t + 2]);
    ear.computeNormals();
  }
  return ear;
}

}  // namespace bake
