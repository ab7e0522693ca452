#pragma once
// Bounds-checked decoding of glTF accessors into flat float or index arrays.
// tinygltf parses the JSON; it does not check that an accessor fits its
// buffer view or that a buffer view fits its buffer, so every read goes
// through here: count x stride is checked against the real buffer size before
// anything is allocated, sparse substitution (with or without a base buffer
// view) is applied, normalized integers are mapped to [-1,1]/[0,1], float
// data must be finite, and every array made is charged to the load's one
// budget (engine/core/load_budget.h) before it is allocated.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"

namespace eng {

// Components of an accessor type (SCALAR 1, VEC2..VEC4 2..4); 0 for matrices and unknown types.
int gltfComponentCount(int type);
// Bytes of one component of a componentType; 0 for unknown types.
size_t gltfComponentSize(int componentType);

class GltfAccessorReader {
 public:
  GltfAccessorReader(const tinygltf::Model& gltf, LoadBudget& budget) : gltf_(gltf), budget_(budget) {}

  // Element count of a valid accessor index; `what` names the use in messages.
  Result<size_t> count(int accessor, std::string_view what) const;

  // Reads an accessor whose type has exactly `components` components
  // (1 = SCALAR, 2..4 = VECn, 16 = MAT4) into count * components floats.
  Result<std::vector<float>> readFloats(int accessor, int components, std::string_view what);
  // Same for SCALAR accessors whose component count per key is up to the caller (animation outputs).
  Result<std::vector<float>> readScalars(int accessor, std::string_view what) { return readFloats(accessor, 1, what); }
  template <int N>
  Result<std::vector<glm::vec<N, float>>> readVec(int accessor, std::string_view what);
  // Unsigned integer SCALAR accessor (UNSIGNED_BYTE/SHORT/INT), not normalized.
  Result<std::vector<uint32_t>> readIndices(int accessor, std::string_view what);

  // Charges data made from accessors (generated normals and indices, triangle
  // lists) to the same budget; callers charge before allocating.
  Result<void> charge(size_t bytes, std::string_view what) { return budget_.charge(bytes, what); }

 private:
  template <class T>
  Result<std::vector<T>> decode(int accessor, int components, bool indices, std::string_view what);

  const tinygltf::Model& gltf_;
  LoadBudget& budget_;
};

template <int N>
Result<std::vector<glm::vec<N, float>>> GltfAccessorReader::readVec(int accessor, std::string_view what) {
  auto flat = readFloats(accessor, N, what);
  if (!flat) return flat.error();
  std::vector<glm::vec<N, float>> out(flat->size() / N);
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < N; ++c) out[i][c] = (*flat)[i * N + c];
  return out;
}

}  // namespace eng
