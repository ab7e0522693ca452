#pragma once
// A model's morph weights as ONE flat float vector, mesh-major: mesh m's
// targets occupy [offset(m), offset(m) + meshes[m].targetNames.size()).
// The runtime keeps one such vector per model instance and the GPU path
// uploads it as is.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

class WeightLayout {
 public:
  explicit WeightLayout(const Model& model);

  // First flat index of mesh `mesh`'s targets; offset(meshCount()) == total().
  // A mesh outside 0..meshCount() has the empty range at the end: total().
  uint32_t offset(int mesh) const;
  // Number of targets of mesh `mesh` (0 for a mesh outside 0..meshCount()-1).
  uint32_t count(int mesh) const;
  uint32_t total() const;
  int meshCount() const { return static_cast<int>(offsets_.size()) - 1; }

  // Target names, flat and mesh-major (one entry per weight).
  std::vector<std::string> names() const;
  // Flat index of target `name` on mesh `mesh`, -1 when the mesh has none.
  int find(int mesh, std::string_view name) const;
  // Sets every weight named `name` (one per mesh that has such a target);
  // returns how many meshes matched. Errors (InvalidArgument, nothing
  // written): weights.size() is not total().
  Result<int> setByName(std::span<float> weights, std::string_view name, float value) const;
  // The meshes' default weights (mesh.weights), flat.
  std::vector<float> defaults() const;
  // The weights of one mesh inside a flat vector. Errors (InvalidArgument):
  // weights.size() is not total(), or no mesh `mesh`.
  Result<std::span<const float>> meshWeights(std::span<const float> weights, int mesh) const;

 private:
  std::vector<uint32_t> offsets_;  // meshCount + 1 entries
  std::vector<std::string> names_;
  std::vector<float> defaults_;
};

}  // namespace eng
