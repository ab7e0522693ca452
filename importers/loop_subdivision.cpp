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

// Every undirected edge once, keyed by eng::undirectedEdgeKey.
struct EdgeTable {
  std::unordered_map<uint64_t, Edge> edges;
  std::vector<uint64_t> order;  // first-seen order: deterministic vertex numbering

  Edge& at(uint32_t a, uint32_t b) { return edges[eng::undirectedEdgeKey(a, b)]; }
};

// Errors: an index count that is not a multiple of three, or an index past the vertices.
eng::Result<void> checkTriangleList(const eng::Primitive& prim, std::string_view what) {
  const uint32_t n = static_cast<uint32_t>(prim.positions.size());
  if (prim.indices.size() % 3 != 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(what) + ": " + std::to_string(prim.indices.size()) + " indices is not a triangle list");
  for (uint32_t i : prim.indices)
    if (i >= n) return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(what) + ": index " + std::to_string(i) + " of " + std::to_string(n) + " vertices");
  return {};
}

// Each edge with the number of triangles on it and the corners opposite it
// (the first two), which the interior edge rule weighs.
EdgeTable collectEdges(const std::vector<uint32_t>& indices) {
  EdgeTable table;
  for (size_t t = 0; t < indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3], c = indices[t + (k + 2) % 3];
      const uint64_t key = eng::undirectedEdgeKey(a, b);
      auto [it, inserted] = table.edges.try_emplace(key, Edge{std::min(a, b), std::max(a, b)});
      if (inserted) table.order.push_back(key);
      if (it->second.faces < 2) it->second.opposite[it->second.faces] = c;
      ++it->second.faces;
    }
  return table;
}

// One row per old vertex: Loop's interior rule, the boundary rule, or
// staying put where neither applies (non-manifold, isolated, or a boundary
// vertex without exactly two boundary neighbours).
void addOldVertexRows(Operator& op, uint32_t n, EdgeTable& table) {
  // Neighbours per old vertex, and which of them lie along a boundary edge.
  std::vector<std::vector<uint32_t>> neighbours(n), boundaryNeighbours(n);
  std::vector<bool> irregular(n, false);
  for (uint64_t key : table.order) {
    const Edge& e = table.edges[key];
    neighbours[e.a].push_back(e.b);
    neighbours[e.b].push_back(e.a);
    if (e.faces == 1) {
      boundaryNeighbours[e.a].push_back(e.b);
      boundaryNeighbours[e.b].push_back(e.a);
    }
    if (e.faces > 2) irregular[e.a] = irregular[e.b] = true;
  }
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
}

// One new vertex per edge, numbered after the old ones in edge order: the
// interior edge rule (3/8 ends, 1/8 opposite corners) or the boundary midpoint.
// Returns the vertex count after subdivision.
uint32_t addEdgeVertexRows(Operator& op, uint32_t n, EdgeTable& table) {
  uint32_t next = n;
  for (uint64_t key : table.order) {
    Edge& e = table.edges[key];
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
  return next;
}

// Every triangle becomes four: three at its corners and one between its edge midpoints.
std::vector<uint32_t> splitTriangles(const std::vector<uint32_t>& oldIndices, EdgeTable& table) {
  std::vector<uint32_t> indices;
  indices.reserve(oldIndices.size() * 4);
  for (size_t t = 0; t < oldIndices.size(); t += 3) {
    const uint32_t a = oldIndices[t], b = oldIndices[t + 1], c = oldIndices[t + 2];
    const uint32_t ab = table.at(a, b).newVertex, bc = table.at(b, c).newVertex, ca = table.at(c, a).newVertex;
    indices.insert(indices.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return indices;
}

// Texture coordinates and vertex colours are not smoothed: old vertices keep
// theirs, edge vertices take their edge's midpoint, so seams and atlases stay
// put.
template <class T>
std::vector<T> interpolateAtMidpoints(const std::vector<T>& values, uint32_t vertexCount, EdgeTable& table) {
  std::vector<T> out = values;
  out.resize(vertexCount);
  for (uint64_t key : table.order) {
    const Edge& e = table.edges[key];
    out[e.newVertex] = 0.5f * (values[e.a] + values[e.b]);
  }
  return out;
}

// The same weights move each target's position deltas (Loop is linear);
// normal deltas are recomputed against the subdivided base's smooth normals.
void subdivideTargets(std::vector<eng::MorphTarget>& targets, const Operator& op, const std::vector<glm::vec3>& positions,
                      const std::vector<glm::vec3>& normals, const std::vector<uint32_t>& indices) {
  for (eng::MorphTarget& target : targets) {
    if (target.positions.empty()) continue;
    target.positions = op.apply(target.positions);
    std::vector<glm::vec3> moved = positions;
    for (size_t v = 0; v < moved.size(); ++v) moved[v] += target.positions[v];
    const std::vector<glm::vec3> movedNormals = eng::computeSmoothNormals(moved, indices);
    target.normals.resize(movedNormals.size());
    for (size_t v = 0; v < movedNormals.size(); ++v) target.normals[v] = movedNormals[v] - normals[v];
    target.tangents.clear();
  }
}

}  // namespace

eng::Result<void> loopSubdivide(eng::Primitive& prim, std::string_view what) {
  eng::LoadBudget budget;
  return loopSubdivide(prim, what, budget);
}

eng::Result<void> loopSubdivide(eng::Primitive& prim, std::string_view what, eng::LoadBudget& budget) {
  if (auto checked = checkTriangleList(prim, what); !checked) return checked.error();
  const uint32_t n = static_cast<uint32_t>(prim.positions.size());
  EdgeTable edges = collectEdges(prim.indices);
  // A vertex per edge: the base (position, normal, uv, colour) and each target's
  // position and normal deltas grow by that, the triangles fourfold.
  const size_t grown = edges.order.size();
  const size_t perVertex = 2 * sizeof(glm::vec3) + sizeof(glm::vec2) + (prim.colors.empty() ? 0 : sizeof(glm::vec4)) +
                           prim.targets.size() * 2 * sizeof(glm::vec3);
  if (auto ok = budget.charge(grown, perVertex, "subdividing (" + std::to_string(n) + " + " + std::to_string(grown) +
                                                    " vertices, " + std::to_string(prim.targets.size()) + " targets)");
      !ok)
    return ok.error().prefixed(std::string(what) + ": ");
  if (auto ok = budget.charge(prim.indices.size() * 3, sizeof(uint32_t), "subdividing the triangles"); !ok)
    return ok.error().prefixed(std::string(what) + ": ");
  Operator op;
  addOldVertexRows(op, n, edges);
  const uint32_t vertexCount = addEdgeVertexRows(op, n, edges);
  std::vector<uint32_t> indices = splitTriangles(prim.indices, edges);

  std::vector<glm::vec3> positions = op.apply(prim.positions);
  if (!prim.texcoords.empty()) prim.texcoords = interpolateAtMidpoints(prim.texcoords, vertexCount, edges);
  if (!prim.colors.empty()) prim.colors = interpolateAtMidpoints(prim.colors, vertexCount, edges);
  const std::vector<glm::vec3> normals = eng::computeSmoothNormals(positions, indices);
  subdivideTargets(prim.targets, op, positions, normals, indices);
  prim.positions = std::move(positions);
  prim.normals = normals;
  prim.indices = std::move(indices);
  prim.tangents.clear();
  return {};
}

}  // namespace importers
