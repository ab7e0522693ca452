#pragma once
// Editing a face's primitives before targets are made for it (mouth_opening,
// eye_opening): vertices copied with every attribute, triangles moved to a
// primitive of their own, and pieces of the built-in head carried in.
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/posed_face.h"
#include "autorig/target_transfer.h"
#include "engine/scene/model.h"

namespace autorig {

// A mesh's name for notes, "mesh 3" when it has none.
std::string meshLabel(const eng::Model& model, size_t mesh);

// Appends vertex v of `from` to `to` (every attribute `from` has, its
// targets' deltas and skinning too) and returns its index in `to`. `to` may
// be `from` (a copy of v in its own primitive); a fresh `to` gets `from`'s
// attributes and target count.
uint32_t appendVertexOf(eng::Primitive& to, const eng::Primitive& from, uint32_t v);

// A primitive of `prim`'s triangles listed in `triangles` (indices of
// triangles, not of vertices) and only the vertices they use, its material.
// `vertexOf` (optional) receives, per new vertex, the one of `prim` it copies.
eng::Primitive withTriangles(const eng::Primitive& prim, std::span<const uint32_t> triangles,
                             std::vector<uint32_t>* vertexOf = nullptr);

// Pieces of the source (the built-in head) carried into a face as primitives
// of the mesh of `host`, moving as its vertex `anchor` does (its skinning,
// its node), with copies of the source's materials and their images (each
// copied once, however many pieces use it).
class CarriedPieces {
 public:
  CarriedPieces(eng::Model& face, const PosedPrimitive& host, uint32_t anchor);

  // Adds the source's posed primitive `piece` with its vertices at `world`
  // (the face's world space); `turn` takes a source direction into the face's
  // world (normals). Returns the vertices added.
  size_t add(const SourceFace& source, size_t piece, std::span<const glm::vec3> world, const glm::mat3& turn);
  // The materials added to the face so far: the source's index -> the face's.
  const std::map<int, int>& materialsMade() const { return materialOf_; }

 private:
  eng::Model& face_;
  const PosedPrimitive& host_;
  uint32_t anchor_;
  std::vector<glm::u16vec4> anchorJoints_;
  std::vector<glm::vec4> anchorWeights_;
  std::map<int, int> materialOf_;  // source material -> the face's copy
  std::map<int, int> imageOf_;     // source image -> the face's copy
};

}  // namespace autorig
