#include "engine/scene/mesh_weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "engine/scene/position_hash.h"

namespace eng {

namespace {

constexpr uint32_t kNone = UINT32_MAX;

// Bit-identical per-vertex values (all of them, for arrays of several per vertex).
template <typename T>
bool same(const std::vector<T>& values, size_t perVertex, uint32_t a, uint32_t b) {
  return values.empty() || std::memcmp(&values[a * perVertex], &values[b * perVertex], sizeof(T) * perVertex) == 0;
}

bool sameShape(const Primitive& p, uint32_t a, uint32_t b) {
  const size_t sets = p.influenceSets();
  if (!same(p.texcoords, 1, a, b) || !same(p.colors, 1, a, b) || !same(p.joints, sets, a, b) ||
      !same(p.jointWeights, sets, a, b))
    return false;
  for (const MorphTarget& t : p.targets)
    if (!same(t.positions, 1, a, b)) return false;
  return true;
}

bool sameShading(const Primitive& p, uint32_t a, uint32_t b) {
  if (!same(p.normals, 1, a, b) || !same(p.tangents, 1, a, b)) return false;
  for (const MorphTarget& t : p.targets)
    if (!same(t.normals, 1, a, b) || !same(t.tangents, 1, a, b)) return false;
  return true;
}

uint32_t rootOf(std::vector<uint32_t>& keeper, uint32_t v) {
  while (keeper[v] != v) v = keeper[v] = keeper[keeper[v]];
  return v;
}

struct Side {
  uint64_t places;  // the edge's two places, lower first
  uint32_t corner;  // the edge's first corner (t * 3 + k): from corner k to k + 1
};

// Each triangle's unit normal (zero where degenerate) and its sides between
// two places, sorted by place pair so the faces round one edge are adjacent.
void sidesByEdge(const Primitive& p, const ExactPositionGroups& groups, std::vector<glm::vec3>& faceNormal,
                 std::vector<Side>& sides) {
  const size_t triangles = p.indices.size() / 3;
  faceNormal.assign(triangles, glm::vec3(0.0f));
  sides.clear();
  sides.reserve(p.indices.size());
  for (size_t t = 0; t < triangles; ++t) {
    const glm::dvec3 a(p.positions[p.indices[t * 3]]), b(p.positions[p.indices[t * 3 + 1]]), c(p.positions[p.indices[t * 3 + 2]]);
    const glm::dvec3 cross = glm::cross(b - a, c - a);
    const double len = glm::length(cross);
    if (!std::isfinite(len) || len <= 0.0) continue;  // degenerate: no side to walk across
    faceNormal[t] = glm::vec3(cross / len);
    for (uint32_t k = 0; k < 3; ++k) {
      const uint64_t from = groups.groupOf[p.indices[t * 3 + k]], to = groups.groupOf[p.indices[t * 3 + (k + 1) % 3]];
      if (from != to) sides.push_back({std::min(from, to) << 32 | std::max(from, to), uint32_t(t * 3 + k)});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) {
    return a.places < b.places || (a.places == b.places && a.corner < b.corner);
  });
}

// Merges, in the forest `keeper`, the copies of a vertex that differ only in
// shading and lie on one surface: two triangles that share an edge's two
// places join their corners there, unless they are two sheets that touch
// there: closing onto each other into a crack (a slit mouth's lips, the upper
// lip's underside on the lower lip's top), or, where more than two faces meet
// at the edge, faces that do not bound one solid (each face is paired with
// the next one round the edge on its inner side).
void joinAcrossHardEdges(const Primitive& p, const ExactPositionGroups& groups, float minCosine,
                         std::vector<uint32_t>& keeper) {
  std::vector<glm::vec3> faceNormal;
  std::vector<Side> sides;
  sidesByEdge(p, groups, faceNormal, sides);
  auto cornerAt = [&](uint32_t corner, uint32_t place) {  // the side's vertex at `place`
    const uint32_t t = corner / 3, k = corner % 3;
    const uint32_t v = p.indices[t * 3 + k];
    return groups.groupOf[v] == place ? v : p.indices[t * 3 + (k + 1) % 3];
  };
  // Joins two faces' corners at the edge's two places unless they close
  // into a crack there: each corner's normal (the face's, where the
  // primitive has none) leans into the other face, the two further apart
  // than minCosine allows.
  auto join = [&](const Side& a, const Side& b, const glm::vec3& acrossA, const glm::vec3& acrossB) {
    for (const uint32_t place : {uint32_t(a.places >> 32), uint32_t(a.places & 0xffffffffu)}) {
      const uint32_t va = cornerAt(a.corner, place), vb = cornerAt(b.corner, place);
      if (va == vb || !sameShape(p, va, vb)) continue;
      const glm::vec3 na = p.normals.empty() ? faceNormal[a.corner / 3] : p.normals[va];
      const glm::vec3 nb = p.normals.empty() ? faceNormal[b.corner / 3] : p.normals[vb];
      if (glm::dot(na, acrossB) > 0.0f && glm::dot(nb, acrossA) > 0.0f && glm::dot(na, nb) < minCosine) continue;
      const uint32_t ra = rootOf(keeper, va), rb = rootOf(keeper, vb);
      if (ra != rb) keeper[std::max(ra, rb)] = std::min(ra, rb);
    }
  };
  constexpr size_t kMostFaces = 8;  // an edge on more faces (a fan of fins) is not a surface to walk
  struct Round {
    double angle;      // the face's half-plane round the edge
    int inward;        // +1: its inner side (against its normal) lies towards larger angles
    glm::vec3 across;  // unit direction from the edge into the face
    size_t side;
  };
  std::array<Round, kMostFaces> round{};
  for (size_t i = 0; i < sides.size();) {
    size_t end = i + 1;
    while (end < sides.size() && sides[end].places == sides[i].places) ++end;
    const size_t faces = end - i;
    if (faces < 2 || faces > kMostFaces) {
      i = end;
      continue;
    }
    const uint32_t from = uint32_t(sides[i].places >> 32);
    const glm::vec3 origin = p.positions[groups.firstVertex[from]];
    const glm::vec3 axis = glm::normalize(p.positions[groups.firstVertex[uint32_t(sides[i].places & 0xffffffffu)]] - origin);
    const glm::vec3 u = glm::normalize(glm::abs(axis.x) < 0.9f ? glm::cross(axis, glm::vec3(1, 0, 0)) : glm::cross(axis, glm::vec3(0, 1, 0)));
    const glm::vec3 w = glm::cross(axis, u);
    for (size_t f = 0; f < faces; ++f) {
      const uint32_t corner = sides[i + f].corner, t = corner / 3, k = corner % 3;
      const glm::vec3 apex = p.positions[p.indices[t * 3 + (k + 2) % 3]] - origin;
      glm::vec3 across = apex - axis * glm::dot(apex, axis);
      const float len = glm::length(across);
      across = len > 0.0f ? across / len : glm::vec3(0.0f);
      round[f] = {std::atan2(double(glm::dot(across, w)), double(glm::dot(across, u))),
                  glm::dot(faceNormal[t], glm::cross(axis, across)) > 0.0f ? -1 : 1, across, i + f};
    }
    if (faces == 2) {
      join(sides[round[0].side], sides[round[1].side], round[0].across, round[1].across);
    } else {
      std::sort(round.begin(), round.begin() + ptrdiff_t(faces), [](const Round& a, const Round& b) { return a.angle < b.angle; });
      auto partner = [&](size_t f) { return round[f].inward > 0 ? (f + 1) % faces : (f + faces - 1) % faces; };
      for (size_t f = 0; f < faces; ++f)
        if (const size_t g = partner(f); f < g && partner(g) == f)
          join(sides[round[f].side], sides[round[g].side], round[f].across, round[g].across);
    }
    i = end;
  }
}

// Keeps the vertices `newIndex` numbers, in that order, `perVertex` values each.
template <typename T>
void compact(std::vector<T>& values, size_t perVertex, const std::vector<uint32_t>& newIndex, size_t kept) {
  if (values.empty()) return;
  std::vector<T> out(kept * perVertex);
  for (size_t v = 0; v < newIndex.size(); ++v)
    if (newIndex[v] != kNone) std::memcpy(&out[newIndex[v] * perVertex], &values[v * perVertex], sizeof(T) * perVertex);
  values = std::move(out);
}

// Appends a copy of vertex v's `perVertex` values.
template <typename T>
void appendCopy(std::vector<T>& values, size_t perVertex, uint32_t v) {
  if (values.empty()) return;
  for (size_t s = 0; s < perVertex; ++s) values.push_back(values[v * perVertex + s]);
}

// Whether every per-vertex array has one entry (or `sets`) per vertex.
bool wellFormed(const Primitive& p) {
  const size_t n = p.vertexCount();
  const size_t sets = p.influenceSets();
  auto sized = [n](const auto& values, size_t perVertex) { return values.empty() || values.size() == n * perVertex; };
  if (!sized(p.normals, 1) || !sized(p.texcoords, 1) || !sized(p.tangents, 1) || !sized(p.colors, 1) ||
      !sized(p.joints, sets) || !sized(p.jointWeights, sets))
    return false;
  for (const MorphTarget& t : p.targets)
    if (!sized(t.positions, 1) || !sized(t.normals, 1) || !sized(t.tangents, 1)) return false;
  return std::all_of(p.indices.begin(), p.indices.end(), [n](uint32_t i) { return i < n; });
}

// A triangle's three corner places, in its winding order.
using TriangleKey = std::array<ExactPosition, 3>;

TriangleKey triangleKey(const Primitive& p, size_t t) {
  return {ExactPosition(p.positions[p.indices[t * 3]]), ExactPosition(p.positions[p.indices[t * 3 + 1]]),
          ExactPosition(p.positions[p.indices[t * 3 + 2]])};
}

bool keyLess(const TriangleKey& a, const TriangleKey& b) {
  for (size_t k = 0; k < 3; ++k) {
    if (a[k].x != b[k].x) return a[k].x < b[k].x;
    if (a[k].y != b[k].y) return a[k].y < b[k].y;
    if (a[k].z != b[k].z) return a[k].z < b[k].z;
  }
  return false;
}

// For each corner of `welded`, the vertex of `original` at the same corner of
// the triangle at the same places (kNone where no triangle of `original` is there).
std::vector<uint32_t> originalCorners(const Primitive& welded, const Primitive& original) {
  std::vector<std::pair<TriangleKey, uint32_t>> sorted;
  sorted.reserve(original.indices.size() / 3);
  for (size_t t = 0; t < original.indices.size() / 3; ++t) sorted.emplace_back(triangleKey(original, t), uint32_t(t));
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return keyLess(a.first, b.first) || (!keyLess(b.first, a.first) && a.second < b.second);
  });
  std::vector<char> used(sorted.size(), 0);
  std::vector<uint32_t> corners(welded.indices.size(), kNone);
  for (size_t t = 0; t < welded.indices.size() / 3; ++t) {
    const TriangleKey key = triangleKey(welded, t);
    auto it = std::lower_bound(sorted.begin(), sorted.end(), key,
                               [](const auto& entry, const TriangleKey& k) { return keyLess(entry.first, k); });
    // Triangles at one place (a doubled face) each take one of the original's.
    while (it != sorted.end() && it->first == key && used[size_t(it - sorted.begin())]) ++it;
    if (it == sorted.end() || it->first != key) continue;
    used[size_t(it - sorted.begin())] = 1;
    for (size_t k = 0; k < 3; ++k) corners[t * 3 + k] = original.indices[size_t(it->second) * 3 + k];
  }
  return corners;
}

// A target's normal deltas made anew at the vertices on a side (sideOf): each from
// the faces about its place that share its rest normal (its side of a hard
// edge), before and after the target's displacement.
void remakeNormalDeltas(MorphTarget& target, const Primitive& p, const std::vector<uint32_t>& sideOf, size_t sides) {
  std::vector<glm::dvec3> before(sides, glm::dvec3(0.0)), after(sides, glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
    if (sideOf[a] == kNone && sideOf[b] == kNone && sideOf[c] == kNone) continue;
    const glm::dvec3 pa(p.positions[a]), pb(p.positions[b]), pc(p.positions[c]);
    const glm::dvec3 ma = pa + glm::dvec3(target.positions[a]), mb = pb + glm::dvec3(target.positions[b]),
                     mc = pc + glm::dvec3(target.positions[c]);
    const glm::dvec3 rest = glm::cross(pb - pa, pc - pa), moved = glm::cross(mb - ma, mc - ma);
    for (uint32_t v : {a, b, c})
      if (sideOf[v] != kNone) before[sideOf[v]] += rest, after[sideOf[v]] += moved;
  }
  auto unit = [](const glm::dvec3& s) {
    const double len = glm::length(s);
    return std::isfinite(len) && len > 1e-15 ? glm::vec3(s / len) : glm::vec3(0.0f);
  };
  for (size_t v = 0; v < sideOf.size(); ++v)
    if (sideOf[v] != kNone) target.normals[v] = unit(after[sideOf[v]]) - unit(before[sideOf[v]]);
}

}  // namespace

size_t weldIdenticalVertices(Primitive& primitive, const WeldOptions& options) {
  const size_t n = primitive.vertexCount();
  if (n == 0) return 0;
  if (!wellFormed(primitive)) return 0;  // malformed: left as it is (the loader has warned)
  // Candidates share a position: only those are compared attribute by attribute.
  const ExactPositionGroups groups = groupExactPositions(primitive.positions);
  if (groups.firstVertex.size() == n) return 0;
  // Each vertex's keeper, the lowest-numbered vertex it merges into (a
  // union-find forest). Identical copies first: the vertices kept so far in
  // each group as a list threaded through nextKept.
  std::vector<uint32_t> keeper(n);
  std::vector<uint32_t> firstKept(groups.firstVertex.size(), kNone), nextKept(n, kNone);
  for (uint32_t v = 0; v < n; ++v) {
    keeper[v] = v;
    uint32_t& head = firstKept[groups.groupOf[v]];
    for (uint32_t k = head; k != kNone; k = nextKept[k])
      if (sameShape(primitive, k, v) && sameShading(primitive, k, v)) {
        keeper[v] = k;
        break;
      }
    if (keeper[v] != v) continue;
    nextKept[v] = head;
    head = v;
  }
  if (options.acrossHardEdges) joinAcrossHardEdges(primitive, groups, options.minNormalCosine, keeper);
  for (uint32_t v = 0; v < n; ++v) keeper[v] = keeper[keeper[v]];  // roots are lower-numbered: one pass flattens
  std::vector<uint32_t> newIndex(n, kNone);
  size_t kept = 0;
  for (uint32_t v = 0; v < n; ++v)
    if (keeper[v] == v) newIndex[v] = uint32_t(kept++);
  if (kept == n) return 0;
  if (options.acrossHardEdges && !primitive.normals.empty()) {  // the merged copies' mean normal
    std::vector<glm::vec3> sum(n, glm::vec3(0.0f));
    for (uint32_t v = 0; v < n; ++v) sum[keeper[v]] += primitive.normals[v];
    for (uint32_t v = 0; v < n; ++v)
      if (keeper[v] == v && glm::length(sum[v]) > 1e-6f) primitive.normals[v] = glm::normalize(sum[v]);
  }
  const size_t sets = primitive.influenceSets();
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

size_t weldIdenticalVertices(Model& model, const WeldOptions& options) {
  size_t removed = 0;
  for (Mesh& mesh : model.meshes)
    for (Primitive& primitive : mesh.primitives) removed += weldIdenticalVertices(primitive, options);
  return removed;
}

namespace {

// A copy of vertex v with every attribute and target delta, at the end; its index.
uint32_t appendVertexCopy(Primitive& p, uint32_t v) {
  const size_t sets = p.influenceSets();
  const uint32_t copy = uint32_t(p.vertexCount());
  p.positions.push_back(p.positions[v]);
  appendCopy(p.normals, 1, v);
  appendCopy(p.texcoords, 1, v);
  appendCopy(p.tangents, 1, v);
  appendCopy(p.colors, 1, v);
  appendCopy(p.joints, sets, v);
  appendCopy(p.jointWeights, sets, v);
  for (MorphTarget& t : p.targets) {
    appendCopy(t.positions, 1, v);
    appendCopy(t.normals, 1, v);
    appendCopy(t.tangents, 1, v);
  }
  return copy;
}

// The normal deltas of the targets from `firstMade` on (made since the file
// was read) remade where a place has more than one normal (the hard edges).
void remakeMadeNormalDeltas(Primitive& welded, size_t firstMade) {
  const ExactPositionGroups groups = groupExactPositions(welded.positions);
  std::vector<char> hard(groups.firstVertex.size(), 0);
  for (size_t v = 0; v < welded.vertexCount(); ++v)
    if (welded.normals[v] != welded.normals[groups.firstVertex[groups.groupOf[v]]]) hard[groups.groupOf[v]] = 1;
  // A side: the vertices at one hard place with one normal; the vertices of
  // each place as a list threaded through nextAtPlace.
  std::vector<uint32_t> firstAtPlace(groups.firstVertex.size(), kNone), nextAtPlace(welded.vertexCount(), kNone);
  std::vector<uint32_t> sideOf(welded.vertexCount(), kNone);
  size_t sides = 0;
  for (size_t v = 0; v < welded.vertexCount(); ++v) {
    const uint32_t g = groups.groupOf[v];
    if (!hard[g]) continue;
    for (uint32_t w = firstAtPlace[g]; w != kNone && sideOf[v] == kNone; w = nextAtPlace[w])
      if (welded.normals[w] == welded.normals[v]) sideOf[v] = sideOf[w];
    if (sideOf[v] == kNone) sideOf[v] = uint32_t(sides++);
    nextAtPlace[v] = firstAtPlace[g];
    firstAtPlace[g] = uint32_t(v);
  }
  if (sides == 0) return;
  for (size_t i = firstMade; i < welded.targets.size(); ++i)
    if (welded.targets[i].normals.size() == welded.vertexCount())
      remakeNormalDeltas(welded.targets[i], welded, sideOf, sides);
}

}  // namespace

size_t restoreHardEdges(Primitive& welded, const Primitive& original) {
  if (!wellFormed(welded) || !wellFormed(original) || welded.normals.empty() || original.normals.empty()) return 0;
  const bool tangents = !welded.tangents.empty() && !original.tangents.empty();
  const std::vector<uint32_t> corners = originalCorners(welded, original);
  // Each corner's vertex: the vertex itself or a copy of it with the shading
  // the corner asks for. The copies of a vertex as a list threaded through nextCopy.
  const size_t n = welded.vertexCount();
  std::vector<uint32_t> firstCopy(n, kNone), nextCopy;
  std::vector<uint32_t> originalOf(n, kNone);  // the original vertex whose shading a vertex took
  std::vector<char> claimed(n, 0);
  auto shadingOf = [&](uint32_t ov, uint32_t v) {
    return std::make_pair(ov == kNone ? welded.normals[v] : original.normals[ov],
                          ov == kNone || !tangents ? (tangents ? welded.tangents[v] : glm::vec4(0.0f)) : original.tangents[ov]);
  };
  auto hasShading = [&](uint32_t v, const std::pair<glm::vec3, glm::vec4>& s) {
    return welded.normals[v] == s.first && (!tangents || welded.tangents[v] == s.second);
  };
  for (size_t c = 0; c < welded.indices.size(); ++c) {
    const uint32_t v = welded.indices[c];
    const auto wanted = shadingOf(corners[c], v);
    if (!claimed[v]) {
      claimed[v] = 1;
      welded.normals[v] = wanted.first;
      if (tangents) welded.tangents[v] = wanted.second;
      originalOf[v] = corners[c];
      continue;
    }
    if (hasShading(v, wanted)) continue;
    uint32_t copy = firstCopy[v];
    while (copy != kNone && !hasShading(copy, wanted)) copy = nextCopy[copy - n];
    if (copy == kNone) {
      copy = appendVertexCopy(welded, v);
      welded.normals[copy] = wanted.first;
      if (tangents) welded.tangents[copy] = wanted.second;
      nextCopy.push_back(firstCopy[v]);
      firstCopy[v] = copy;
      originalOf.push_back(corners[c]);
    }
    welded.indices[c] = copy;
  }
  const size_t added = welded.vertexCount() - n;
  // The original's own targets keep its normal deltas; those made since are
  // remade where a place has more than one normal (the hard edges).
  const size_t own = std::min(original.targets.size(), welded.targets.size());
  for (size_t i = 0; i < own; ++i) {
    MorphTarget& t = welded.targets[i];
    const MorphTarget& o = original.targets[i];
    for (size_t v = 0; v < originalOf.size(); ++v) {
      if (originalOf[v] == kNone) continue;
      if (!t.normals.empty() && !o.normals.empty()) t.normals[v] = o.normals[originalOf[v]];
      if (!t.tangents.empty() && !o.tangents.empty()) t.tangents[v] = o.tangents[originalOf[v]];
    }
  }
  if (own < welded.targets.size()) remakeMadeNormalDeltas(welded, own);
  return added;
}

}  // namespace eng
