#pragma once
// A model's triangles in world space for picking and sculpting: every
// primitive of every mesh placed by a node (the first node placing it), its
// rest positions and its positions posed by morph weights (CPU morphing, the
// same sum the GPU does), in one flat vertex array. Ray casts hit the posed
// surface and report the matching rest point, so a control point picked on a
// smiling face lands on the same spot of the neutral one.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace editor {

struct SurfacePrimitive {
  int mesh = -1;
  int primitive = -1;
  size_t firstVertex = 0;  // into ModelSurface's flat arrays
  size_t vertexCount = 0;
  glm::mat4 world{1.0f};
  glm::mat3 worldToLocal{1.0f};  // for directions (displacements)
};

struct SurfaceHit {
  float distance = 0;      // along the ray (in units of the ray direction's length)
  size_t primitive = 0;    // index into ModelSurface::primitives()
  uint32_t triangle = 0;
  glm::vec3 barycentric{0.0f};
  glm::vec3 posedPoint{0.0f};
  glm::vec3 restPoint{0.0f};
};

class ModelSurface {
 public:
  // Fails when no node places a mesh with triangles.
  static eng::Result<ModelSurface> create(const eng::Model& model);

  std::span<const SurfacePrimitive> primitives() const { return primitives_; }
  std::span<const glm::vec3> restPositions() const { return rest_; }
  std::span<const glm::vec3> posedPositions() const { return posed_; }
  size_t vertexCount() const { return rest_.size(); }

  // Poses with the model's flat weights (eng::WeightLayout order). Fails on a
  // size mismatch (naming both sizes); nothing changes then.
  eng::Result<void> pose(const eng::Model& model, std::span<const float> weights);
  // Nearest hit of the ray origin + s * direction (s > 0) with the posed surface.
  std::optional<SurfaceHit> raycast(const eng::Model& model, const glm::vec3& origin, const glm::vec3& direction) const;

 private:
  std::vector<SurfacePrimitive> primitives_;
  std::vector<glm::vec3> rest_;
  std::vector<glm::vec3> posed_;
  std::vector<glm::vec3> scratch_;
};

}  // namespace editor
