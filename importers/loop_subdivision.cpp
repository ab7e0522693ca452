#include "importers/loop_subdivision.h"

#include "engine/scene/edge_key.h"

#include <string>
#include <unordered_map>
#include <vector>

#include "engine/scene/normals.h"

namespace importers {
namespace {

struct Edge {
  uint32_t a, b;                          // a < b
  uint32_t opposite[2] = {UINT32_MAX, UINT32_MAX};
  uint32_t faces = 0;
  uint32_t newVertex = 0;
};

// New vertex = sum of weight * old vertex, as flat rows.
struct Operator {
  std::vector<uint32_t> rowStart{0};
  std::vector<uint32_t> source;
  std::vector<float> weight;

  void add(uint32_t s, float w) {
    source.push_back(s);
    weight.push_back(w);
  }
  void endRow() { rowStart.push_back(static_cast<uint32_t>(source.size())); }
  size_t rows() const { return rowStart.size() - 1; }

  template <typename T>
  std::vector<T> apply(const std::vector<T>& in) const {
    std::vector<T> out(rows(), T(0.0f));
    for (size_t r = 0; r < rows(); ++r)
      for (uint32_t k = rowStart[r]; k < rowStart[r + 1]; ++k) out[r] += weight[k] * in[source[k]];
    return out;
  }
};

}  // namespace

eng::Result<void> loopSubdivide(eng::Primitive& prim, std::string_view what) {
  const uint32_t n = static_cast<uint32_t>(prim.positions.size());
  if (prim.indices.size() % 3 != 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(what) + ": " + std::to_string(prim.indices.size()) + " indices is not a triangle list");
  for (uint32_t i : prim.indices)
    if (i >= n) return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(what) + ": index " + std::to_string(i) + " of " + std::to_string(n) + " vertices");

  std::unordered_map<uint64_t, Edge> edges;
  std::vector<uint64_t> edgeOrder;  // first-seen order: deterministic vertex numbering
  for (size_t t = 0; t < prim.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = prim.indices[t + k], b = prim.indices[t + (k + 1) % 3], c = prim.indices[t + (k + 2) % 3];
      const uint64_t key = eng::undirectedEdgeKey(a, b);
      auto [it, inserted] = edges.try_emplace(key, Edge{std::min(a, b), std::max(a, b)});
      if (inserted) edgeOrder.push_back(key);
      if (it->second.faces < 2) it->second.opposite[it->second.faces] = c;
      ++it->second.faces;
    }

  // Neighbours per old vertex, and which of them lie along a boundary edge.
  std::vector<std::vector<uint32_t>> neighbours(n), boundaryNeighbours(n);
  std::vector<bool> irregular(n, false);
  for (uint64_t key : edgeOrder) {
    const Edge& e = edges[key];
    neighbours[e.a].push_back(e.b);
    neighbours[e.b].push_back(e.a);
    if (e.faces == 1) {
      boundaryNeighbours[e.a].push_back(e.b);
      boundaryNeighbours[e.b].push_back(e.a);
    }
    if (e.faces > 2) irregular[e.a] = irregular[e.b] = true;
  }

  Operator op;
  for (uint32_t v = 0; v < n; ++v) {
    const size_t k = neighbours[v].size();
    if (irregular[v] || k == 0 || (!boundaryNeighbours[v].empty() && boundaryNeighbours[v].size() != 2)) {
      op.add(v, 1.0f);
    } else if (boundaryNeighbours[v].size() == 2) {
      op.add(v, 0.75f);
      op.add(boundaryNeighbours[v][0], 0.125f);
      op.add(boundaryNeighbours[v][1], 0.125f);
    } else {
      const float beta = k == 3 ? 3.0f / 16.0f : 3.0f / (8.0f * float(k));
      op.add(v, 1.0f - float(k) * beta);
      for (uint32_t u : neighbours[v]) op.add(u, beta);
    }
    op.endRow();
  }
  uint32_t next = n;
  for (uint64_t key : edgeOrder) {
    Edge& e = edges[key];
    e.newVertex = next++;
    if (e.faces == 2) {
      op.add(e.a, 0.375f);
      op.add(e.b, 0.375f);
      op.add(e.opposite[0], 0.125f);
      op.add(e.opposite[1], 0.125f);
    } else {
      op.add(e.a, 0.5f);
      op.add(e.b, 0.5f);
    }
    op.endRow();
  }

  std::vector<uint32_t> indices;
  indices.reserve(prim.indices.size() * 4);
  for (size_t t = 0; t < prim.indices.size(); t += 3) {
    const uint32_t a = prim.indices[t], b = prim.indices[t + 1], c = prim.indices[t + 2];
    const uint32_t ab = edges[eng::undirectedEdgeKey(a, b)].newVertex, bc = edges[eng::undirectedEdgeKey(b, c)].newVertex,
                   ca = edges[eng::undirectedEdgeKey(c, a)].newVertex;
    indices.insert(indices.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }

  std::vector<glm::vec3> positions = op.apply(prim.positions);
  if (!prim.texcoords.empty()) {
    std::vector<glm::vec2> uv = prim.texcoords;
    uv.resize(next);
    for (uint64_t key : edgeOrder) {
      const Edge& e = edges[key];
      uv[e.newVertex] = 0.5f * (prim.texcoords[e.a] + prim.texcoords[e.b]);
    }
    prim.texcoords = std::move(uv);
  }
  const std::vector<glm::vec3> normals = eng::computeSmoothNormals(positions, indices);
  for (eng::MorphTarget& target : prim.targets) {
    if (target.positions.empty()) continue;
    target.positions = op.apply(target.positions);
    std::vector<glm::vec3> moved = positions;
    for (size_t v = 0; v < moved.size(); ++v) moved[v] += target.positions[v];
    const std::vector<glm::vec3> movedNormals = eng::computeSmoothNormals(moved, indices);
    target.normals.resize(movedNormals.size());
    for (size_t v = 0; v < movedNormals.size(); ++v) target.normals[v] = movedNormals[v] - normals[v];
    target.tangents.clear();
  }
  prim.positions = std::move(positions);
  prim.normals = normals;
  prim.indices = std::move(indices);
  prim.tangents.clear();
  return {};
}

}  // namespace importers
