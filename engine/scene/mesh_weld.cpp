#include "engine/scene/mesh_weld.h"

#include <cstring>
#include <vector>

#include "engine/scene/position_hash.h"

namespace eng {

namespace {

// Bit-identical per-vertex values (all of them, for arrays of several per vertex).
template <typename T>
bool same(const std::vector<T>& values, size_t perVertex, uint32_t a, uint32_t b) {
  return values.empty() || std::memcmp(&values[a * perVertex], &values[b * perVertex], sizeof(T) * perVertex) == 0;
}

bool identical(const Primitive& p, uint32_t a, uint32_t b) {
  const size_t sets = p.influenceSets();
  if (!same(p.normals, 1, a, b) || !same(p.texcoords, 1, a, b) || !same(p.tangents, 1, a, b) ||
      !same(p.colors, 1, a, b) || !same(p.joints, sets, a, b) || !same(p.jointWeights, sets, a, b))
    return false;
  for (const MorphTarget& t : p.targets)
    if (!same(t.positions, 1, a, b) || !same(t.normals, 1, a, b) || !same(t.tangents, 1, a, b)) return false;
  return true;
}

// Keeps the vertices `kept` marks, in order, `perVertex` values each.
template <typename T>
void compact(std::vector<T>& values, size_t perVertex, const std::vector<uint32_t>& newIndex, size_t kept) {
  if (values.empty()) return;
  std::vector<T> out(kept * perVertex);
  for (size_t v = 0; v < newIndex.size(); ++v)
    if (newIndex[v] != UINT32_MAX)
      std::memcpy(&out[newIndex[v] * perVertex], &values[v * perVertex], sizeof(T) * perVertex);
  values = std::move(out);
}

}  // namespace

size_t weldIdenticalVertices(Primitive& primitive) {
  const size_t n = primitive.vertexCount();
  if (n == 0) return 0;
  auto sized = [n](const auto& values, size_t perVertex) { return values.empty() || values.size() == n * perVertex; };
  const size_t sets = primitive.influenceSets();
  if (!sized(primitive.normals, 1) || !sized(primitive.texcoords, 1) || !sized(primitive.tangents, 1) ||
      !sized(primitive.colors, 1) || !sized(primitive.joints, sets) || !sized(primitive.jointWeights, sets))
    return 0;  // malformed: left as it is (the loader has warned)
  for (const MorphTarget& t : primitive.targets)
    if (!sized(t.positions, 1) || !sized(t.normals, 1) || !sized(t.tangents, 1)) return 0;
  for (uint32_t i : primitive.indices)
    if (i >= n) return 0;
  // Candidates share a position: only those are compared attribute by attribute.
  const ExactPositionGroups groups = groupExactPositions(primitive.positions);
  if (groups.firstVertex.size() == n) return 0;
  std::vector<std::vector<uint32_t>> keptInGroup(groups.firstVertex.size());
  std::vector<uint32_t> keeper(n);
  std::vector<uint32_t> newIndex(n, UINT32_MAX);
  size_t kept = 0;
  for (uint32_t v = 0; v < n; ++v) {
    keeper[v] = v;
    for (uint32_t k : keptInGroup[groups.groupOf[v]])
      if (identical(primitive, k, v)) {
        keeper[v] = k;
        break;
      }
    if (keeper[v] != v) continue;
    keptInGroup[groups.groupOf[v]].push_back(v);
    newIndex[v] = uint32_t(kept++);
  }
  if (kept == n) return 0;
  for (uint32_t& i : primitive.indices) i = newIndex[keeper[i]];
  compact(primitive.positions, 1, newIndex, kept);
  compact(primitive.normals, 1, newIndex, kept);
  compact(primitive.texcoords, 1, newIndex, kept);
  compact(primitive.tangents, 1, newIndex, kept);
  compact(primitive.colors, 1, newIndex, kept);
  compact(primitive.joints, sets, newIndex, kept);
  compact(primitive.jointWeights, sets, newIndex, kept);
  for (MorphTarget& t : primitive.targets) {
    compact(t.positions, 1, newIndex, kept);
    compact(t.normals, 1, newIndex, kept);
    compact(t.tangents, 1, newIndex, kept);
  }
  return n - kept;
}

size_t weldIdenticalVertices(Model& model) {
  size_t removed = 0;
  for (Mesh& mesh : model.meshes)
    for (Primitive& primitive : mesh.primitives) removed += weldIdenticalVertices(primitive);
  return removed;
}

}  // namespace eng
