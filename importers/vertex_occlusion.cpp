#include "importers/vertex_occlusion.h"

#include "engine/scene/skeleton_pose.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

class VoxelGrid {
 public:
  VoxelGrid(const Aabb& bounds, int resolution) : origin_(bounds.min) {
    const float longest = std::max({bounds.size().x, bounds.size().y, bounds.size().z, 1e-6f});
    voxel_ = longest / float(resolution);
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, int(std::ceil(bounds.size()[a] / voxel_)) + 2);
    origin_ -= glm::vec3(voxel_);
    cells_.assign(size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]), 0);
  }

  float voxel() const { return voxel_; }

  void markTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // Samples closer than half a voxel apart: every voxel the triangle crosses is marked.
    const float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    const int steps = std::clamp(int(std::ceil(longest / (0.5f * voxel_))), 1, 512);
    for (int i = 0; i <= steps; ++i) {
      for (int j = 0; j <= steps - i; ++j) {
        const float u = float(i) / float(steps), v = float(j) / float(steps);
        mark(a + (b - a) * u + (c - a) * v);
      }
    }
  }

  bool occupied(const glm::vec3& p) const {
    const glm::ivec3 q = cell(p);
    if (q.x < 0 || q.y < 0 || q.z < 0 || q.x >= dims_[0] || q.y >= dims_[1] || q.z >= dims_[2]) return false;
    return cells_[index(q)] != 0;
  }

 private:
  glm::ivec3 cell(const glm::vec3& p) const { return glm::ivec3(glm::floor((p - origin_) / voxel_)); }
  size_t index(const glm::ivec3& q) const {
    return (size_t(q.z) * size_t(dims_[1]) + size_t(q.y)) * size_t(dims_[0]) + size_t(q.x);
  }
  void mark(const glm::vec3& p) {
    const glm::ivec3 q = cell(p);
    if (q.x < 0 || q.y < 0 || q.z < 0 || q.x >= dims_[0] || q.y >= dims_[1] || q.z >= dims_[2]) return;
    cells_[index(q)] = 1;
  }

  glm::vec3 origin_;
  float voxel_ = 1.0f;
  int dims_[3] = {1, 1, 1};
  std::vector<uint8_t> cells_;
};

// Cosine-distributed directions around +Z (a Fibonacci spiral over the disc,
// lifted onto the hemisphere): even coverage with no random noise, the same
// on every run.
std::vector<glm::vec3> hemisphereDirections(int count) {
  std::vector<glm::vec3> dirs;
  const float golden = 2.39996323f;
  for (int i = 0; i < count; ++i) {
    const float r = std::sqrt((float(i) + 0.5f) / float(count));
    const float phi = float(i) * golden;
    dirs.push_back({r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - r * r))});
  }
  return dirs;
}

}  // namespace

std::vector<std::vector<std::vector<float>>> bakeVertexOcclusion(const Model& model, const OcclusionOptions& options) {
  std::vector<std::vector<std::vector<float>>> visibility(model.meshes.size());
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    visibility[m].resize(model.meshes[m].primitives.size());
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      visibility[m][p].assign(model.meshes[m].primitives[p].positions.size(), 1.0f);
  }
  // Each mesh's first drawing node places it.
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  std::vector<glm::mat4> world(model.meshes.size(), glm::mat4(1.0f));
  const std::vector<glm::mat4> nodeWorld = restWorldMatrices(model);
  Aabb bounds;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (nodeOfMesh[m] < 0) continue;
    world[m] = nodeWorld[size_t(nodeOfMesh[m])];
    for (const Primitive& prim : model.meshes[m].primitives)
      for (const glm::vec3& p : prim.positions) bounds.extend(glm::vec3(world[m] * glm::vec4(p, 1.0f)));
  }
  if (!bounds.valid()) return visibility;

  VoxelGrid grid(bounds, std::max(8, options.resolution));
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (nodeOfMesh[m] < 0) continue;
    for (const Primitive& prim : model.meshes[m].primitives) {
      for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
        const uint32_t a = prim.indices[i], b = prim.indices[i + 1], c = prim.indices[i + 2];
        if (a >= prim.positions.size() || b >= prim.positions.size() || c >= prim.positions.size()) continue;
        grid.markTriangle(glm::vec3(world[m] * glm::vec4(prim.positions[a], 1.0f)),
                          glm::vec3(world[m] * glm::vec4(prim.positions[b], 1.0f)),
                          glm::vec3(world[m] * glm::vec4(prim.positions[c], 1.0f)));
      }
    }
  }

  const std::vector<glm::vec3> dirs = hemisphereDirections(std::max(4, options.rays));
  const float longest = std::max({bounds.size().x, bounds.size().y, bounds.size().z});
  const float step = grid.voxel() * 0.75f;
  const int steps = std::max(2, int(options.reach * longest / step));
  // Rays start two voxels off the surface, past the vertex's own voxels.
  const float start = 2.0f * grid.voxel();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (nodeOfMesh[m] < 0) continue;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world[m])));
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const Primitive& prim = model.meshes[m].primitives[p];
      for (size_t v = 0; v < prim.positions.size() && v < prim.normals.size(); ++v) {
        glm::vec3 n = normalMatrix * prim.normals[v];
        if (!(glm::dot(n, n) > 1e-20f)) continue;
        n = glm::normalize(n);
        const glm::vec3 t = glm::normalize(std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                                                : glm::cross(n, glm::vec3(0, 1, 0)));
        const glm::vec3 b = glm::cross(n, t);
        const glm::vec3 origin = glm::vec3(world[m] * glm::vec4(prim.positions[v], 1.0f));
        int open = 0;
        for (const glm::vec3& d : dirs) {
          const glm::vec3 dir = t * d.x + b * d.y + n * d.z;
          bool hit = false;
          for (int s = 0; s < steps && !hit; ++s) hit = grid.occupied(origin + dir * (start + step * float(s)));
          open += hit ? 0 : 1;
        }
        visibility[m][p][v] = float(open) / float(dirs.size());
      }
    }
  }
  return visibility;
}

}  // namespace importers
