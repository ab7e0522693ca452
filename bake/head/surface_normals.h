#pragma once
// Smooth normals over a surface whose points may be split into several
// vertices (texture seams, primitive borders): face normals are summed per
// weld id, not per position, so the two coincident sides of the lip seam keep
// their own normals while texture seams stay invisible.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bake {

// weldIds[v] < positions.size(); vertices on no triangle get (0, 0, 1).
std::vector<glm::vec3> weldedNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                     std::span<const uint32_t> weldIds);

}  // namespace bake
