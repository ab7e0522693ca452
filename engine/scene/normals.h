#pragma once
// Smooth vertex normals for meshes that come without them.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

// Area-weighted face normals summed per vertex, then shared between vertices
// at the same position, so texture seams (split vertices) stay smooth.
// indices: triangle list; out-of-range triangles are ignored. Vertices on no
// triangle get (0, 0, 1).
std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

}  // namespace eng
