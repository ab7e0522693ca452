#pragma once
// A face in its rest pose, in world space: every drawn primitive morphed by
// the mesh's default weights and skinned in the rest pose, as the renderer
// draws it. Landmarks are found and targets are transferred in this space;
// toLocal() takes a world-space displacement back into the primitive's own
// (bind) space, where glTF morph target deltas live.
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace autorig {

struct PosedPrimitive {
  size_t mesh = 0;       // index into Model::meshes
  size_t primitive = 0;  // index into Mesh::primitives
  int node = -1;         // the first scene node drawing the mesh
  std::vector<glm::vec3> positions;  // world space, vertexCount long
  // Per vertex: the inverse of the linear part of (node world x skin) at
  // rest, so toLocal(v, worldDelta) is the mesh-space delta that moves the
  // drawn vertex by worldDelta.
  std::vector<glm::mat3> worldToLocal;

  glm::vec3 toLocal(size_t vertex, const glm::vec3& worldDelta) const { return worldToLocal[vertex] * worldDelta; }
};

struct PosedFace {
  std::vector<PosedPrimitive> primitives;  // mesh-major, primitive order; undrawn meshes left out

  // The posed primitive of (mesh, primitive), or null when it is not drawn.
  const PosedPrimitive* find(size_t mesh, size_t primitive) const;
  size_t vertexCount() const;
};

// Poses every primitive drawn by the model's scene at rest (default weights).
PosedFace poseAtRest(const eng::Model& model);

}  // namespace autorig
