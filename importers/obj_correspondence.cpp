#include "importers/obj_correspondence.h"

#include <algorithm>
#include <deque>
#include <unordered_map>

#include "engine/core/work_counter.h"
#include "engine/scene/position_hash.h"

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

// Candidates looked at per vertex when matching by position: seams and
// stacked duplicates have a handful, a hostile pile thousands.
constexpr size_t kMaxCandidates = 64;

std::string faceVertices(const ObjPolygonMesh& mesh, size_t f) {
  std::string s = "v[";
  for (size_t k = 0; k < mesh.faceSize(f); ++k) s += (k ? " " : "") + std::to_string(mesh.corner(f, k).v + 1);
  return s + "]";
}

uint64_t edgeKey(int32_t a, int32_t b) { return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b); }

}  // namespace

Result<ObjCornerMap> matchObjByTopology(const ObjPolygonMesh& neutral, const ObjPolygonMesh& target,
                                        const std::string& neutralName, const std::string& targetName) {
  const size_t nv = neutral.positions.size(), tv = target.positions.size();
  const size_t nf = neutral.faceCount(), tf = target.faceCount();
  std::string firstDifference;
  for (size_t f = 0; f < std::min(nf, tf) && firstDifference.empty(); ++f) {
    bool same = neutral.faceSize(f) == target.faceSize(f);
    for (size_t k = 0; same && k < neutral.faceSize(f); ++k) same = neutral.corner(f, k).v == target.corner(f, k).v;
    if (!same)
      firstDifference = "first differing face " + std::to_string(f + 1) + " is " + faceVertices(target, f) + " here, " +
                        faceVertices(neutral, f) + " in the neutral";
  }
  if (nv != tv || nf != tf || !firstDifference.empty()) {
    if (firstDifference.empty())
      firstDifference = "the first " + std::to_string(std::min(nf, tf)) + " faces agree";
    return makeError(ErrorKind::Malformed, targetName + ": topology differs from " + neutralName + " (" + std::to_string(tv) + " vertices vs " +
                     std::to_string(nv) + ", " + std::to_string(tf) + " faces vs " + std::to_string(nf) + "); " +
                     firstDifference + "; vertex and face order must match the neutral (or use --match-by-position)");
  }
  ObjCornerMap map;
  map.targetCorner.resize(neutral.corners.size());
  for (size_t c = 0; c < map.targetCorner.size(); ++c) map.targetCorner[c] = static_cast<int32_t>(c);
  map.targetVertex.resize(nv);
  for (size_t v = 0; v < nv; ++v) map.targetVertex[v] = static_cast<int32_t>(v);
  return map;
}

ObjCornerMap matchObjByPosition(const ObjPolygonMesh& neutral, const ObjPolygonMesh& target, float tolerance) {
  ObjCornerMap map;
  const size_t nv = neutral.positions.size();
  map.targetCorner.assign(neutral.corners.size(), -1);
  map.targetVertex.assign(nv, -1);
  std::vector<bool> claimed(target.positions.size(), false);

  // 1. Vertices that did not move: nearest unclaimed target vertex within
  //    tolerance, among a bounded number of candidates (a pile of coincident
  //    points is left to step 2 past it, not searched whole per vertex).
  const PositionHash hash(target.positions, tolerance);
  for (size_t v = 0; v < nv; ++v) {
    const int64_t t = hash.nearestFree(neutral.positions[v], tolerance, claimed, kMaxCandidates);
    if (t < 0) continue;
    claimed[size_t(t)] = true;
    map.targetVertex[v] = static_cast<int32_t>(t);
  }

  // 2. Spread across edges: a neutral face with one edge whose ends are both
  //    matched maps onto the target face owning that directed edge.
  std::vector<int32_t> targetFaceOfCorner(target.corners.size());
  std::unordered_map<uint64_t, uint32_t> targetEdges;  // directed (v_k, v_k+1) -> flat corner of v_k
  targetEdges.reserve(target.corners.size());
  for (size_t f = 0; f < target.faceCount(); ++f) {
    const size_t n = target.faceSize(f);
    for (size_t k = 0; k < n; ++k) {
      targetFaceOfCorner[target.faceStart[f] + k] = static_cast<int32_t>(f);
      targetEdges.try_emplace(edgeKey(target.corner(f, k).v, target.corner(f, (k + 1) % n).v),
                              static_cast<uint32_t>(target.faceStart[f] + k));
    }
  }
  // Faces around each neutral vertex (CSR), to revisit them when it gets matched.
  std::vector<uint32_t> adjacencyStart(nv + 1, 0), adjacency;
  for (const ObjCorner& c : neutral.corners) ++adjacencyStart[c.v + 1];
  for (size_t v = 0; v < nv; ++v) adjacencyStart[v + 1] += adjacencyStart[v];
  adjacency.resize(neutral.corners.size());
  {
    std::vector<uint32_t> fill(adjacencyStart.begin(), adjacencyStart.end() - 1);
    for (size_t f = 0; f < neutral.faceCount(); ++f)
      for (size_t k = 0; k < neutral.faceSize(f); ++k) adjacency[fill[neutral.corner(f, k).v]++] = static_cast<uint32_t>(f);
  }

  std::vector<bool> resolved(neutral.faceCount(), false);
  std::deque<uint32_t> queue;
  for (size_t f = 0; f < neutral.faceCount(); ++f) queue.push_back(static_cast<uint32_t>(f));
  while (!queue.empty()) {
    const uint32_t f = queue.front();
    queue.pop_front();
    countWork();
    if (resolved[f]) continue;
    const size_t n = neutral.faceSize(f);
    for (size_t j = 0; j < n && !resolved[f]; ++j) {
      const int32_t a = map.targetVertex[neutral.corner(f, j).v];
      const int32_t b = map.targetVertex[neutral.corner(f, (j + 1) % n).v];
      if (a < 0 || b < 0) continue;
      const auto edge = targetEdges.find(edgeKey(a, b));
      if (edge == targetEdges.end()) continue;
      const int32_t tf = targetFaceOfCorner[edge->second];
      if (target.faceSize(tf) != n) continue;
      const size_t k = edge->second - target.faceStart[tf];
      resolved[f] = true;
      for (size_t i = 0; i < n; ++i) {
        const size_t tc = target.faceStart[tf] + (k + n - j + i) % n;
        map.targetCorner[neutral.faceStart[f] + i] = static_cast<int32_t>(tc);
        const int32_t v = neutral.corner(f, i).v;
        const int32_t t = target.corners[tc].v;
        if (map.targetVertex[v] < 0 && !claimed[t]) {
          claimed[t] = true;
          map.targetVertex[v] = t;
          for (uint32_t i2 = adjacencyStart[v]; i2 < adjacencyStart[v + 1]; ++i2)
            if (!resolved[adjacency[i2]]) queue.push_back(adjacency[i2]);
        }
      }
    }
  }
  for (size_t v = 0; v < nv; ++v)
    if (map.targetVertex[v] < 0 && adjacencyStart[v + 1] > adjacencyStart[v]) ++map.unmatchedVertices;
  return map;
}

}  // namespace importers
