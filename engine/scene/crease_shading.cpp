#include "engine/scene/crease_shading.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "engine/scene/position_hash.h"

namespace eng {
namespace {

// How a measured fold becomes darkness. A vertex that sinks by a third of
// its edge length relative to its neighbours (a furrow forming) darkens by
// about half; a ring that loses a third of its area (skin bunching) by a
// quarter. Chosen on the built-in head and facecap so a full-strength brow
// lowerer draws the vertical furrows between the brows without darkening a
// smile's cheeks into dirt.
constexpr float kConcavityGain = 1.5f;
constexpr float kCompressionGain = 0.8f;
// Below this a target is treated as not creasing the vertex at all (noise
// from sliding, rotating regions).
constexpr float kThreshold = 0.03f;

// Vertices split at seams (same position) become one node, so the fold is
// measured on the surface rather than on each side of a UV cut.
struct WeldedSurface {
  std::vector<uint32_t> nodeOf;         // vertex -> node
  std::vector<uint32_t> firstVertex;    // node -> one of its vertices
  std::vector<uint32_t> ringOffsets;    // node -> [begin, end) into ring
  std::vector<uint32_t> ring;           // neighbour nodes
  std::vector<uint32_t> triangles;      // node indices, 3 per triangle
};

WeldedSurface weld(const Primitive& p) {
  WeldedSurface s;
  ExactPositionGroups groups = groupExactPositions(p.positions);
  s.nodeOf = std::move(groups.groupOf);
  s.firstVertex = std::move(groups.firstVertex);
  const size_t nodeCount = s.firstVertex.size();
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(p.indices.size() * 2);
  for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const uint32_t i[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
    if (i[0] >= p.positions.size() || i[1] >= p.positions.size() || i[2] >= p.positions.size()) continue;
    const uint32_t n[3] = {s.nodeOf[i[0]], s.nodeOf[i[1]], s.nodeOf[i[2]]};
    if (n[0] == n[1] || n[1] == n[2] || n[0] == n[2]) continue;
    s.triangles.insert(s.triangles.end(), n, n + 3);
    for (int e = 0; e < 3; ++e) {
      edges.emplace_back(n[e], n[(e + 1) % 3]);
      edges.emplace_back(n[(e + 1) % 3], n[e]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  s.ringOffsets.assign(nodeCount + 1, 0);
  for (const auto& e : edges) ++s.ringOffsets[e.first + 1];
  for (size_t n = 0; n < nodeCount; ++n) s.ringOffsets[n + 1] += s.ringOffsets[n];
  s.ring.reserve(edges.size());
  for (const auto& e : edges) s.ring.push_back(e.second);
  return s;
}

// Per node: the one-ring Laplacian's component along the rest normal
// (positive = the node lies below its neighbours: a valley) and the area of
// the triangles around it.
struct Shape {
  std::vector<float> depth;
  std::vector<float> area;
};

Shape measure(const WeldedSurface& s, const std::vector<glm::vec3>& position, const std::vector<glm::vec3>& normal) {
  const size_t nodeCount = s.firstVertex.size();
  Shape shape{std::vector<float>(nodeCount, 0.0f), std::vector<float>(nodeCount, 0.0f)};
  for (size_t n = 0; n < nodeCount; ++n) {
    const uint32_t begin = s.ringOffsets[n], end = s.ringOffsets[n + 1];
    if (begin == end) continue;
    glm::vec3 mean(0.0f);
    for (uint32_t r = begin; r < end; ++r) mean += position[s.ring[r]];
    mean /= float(end - begin);
    shape.depth[n] = glm::dot(mean - position[n], normal[n]);
  }
  for (size_t t = 0; t < s.triangles.size(); t += 3) {
    const glm::vec3& a = position[s.triangles[t]];
    const glm::vec3& b = position[s.triangles[t + 1]];
    const glm::vec3& c = position[s.triangles[t + 2]];
    const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) shape.area[s.triangles[t + size_t(k)]] += area;
  }
  return shape;
}

}  // namespace

std::vector<std::vector<float>> bakeCreaseDarkening(const Primitive& p) {
  if (p.targets.empty() || p.indices.size() < 3) return {};
  const WeldedSurface s = weld(p);
  const size_t nodeCount = s.firstVertex.size();
  if (s.triangles.empty()) return {};

  std::vector<glm::vec3> rest(nodeCount), normal(nodeCount, glm::vec3(0.0f));
  for (size_t n = 0; n < nodeCount; ++n) rest[n] = p.positions[s.firstVertex[n]];
  for (size_t t = 0; t < s.triangles.size(); t += 3) {
    const uint32_t a = s.triangles[t], b = s.triangles[t + 1], c = s.triangles[t + 2];
    const glm::vec3 face = glm::cross(rest[b] - rest[a], rest[c] - rest[a]);
    normal[a] += face, normal[b] += face, normal[c] += face;
  }
  std::vector<float> edge(nodeCount, 0.0f);  // mean edge length: the scale a fold is measured in
  for (size_t n = 0; n < nodeCount; ++n) {
    const float len = glm::length(normal[n]);
    normal[n] = len > 0.0f ? normal[n] / len : glm::vec3(0.0f);
    const uint32_t begin = s.ringOffsets[n], end = s.ringOffsets[n + 1];
    for (uint32_t r = begin; r < end; ++r) edge[n] += glm::length(rest[s.ring[r]] - rest[n]);
    if (end > begin) edge[n] /= float(end - begin);
  }
  const Shape restShape = measure(s, rest, normal);

  const size_t vertexCount = p.positions.size();
  std::vector<std::vector<float>> darkening(p.targets.size());
  std::vector<glm::vec3> posed(nodeCount);
  std::vector<float> raw(nodeCount), smoothed(nodeCount);
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const std::vector<glm::vec3>& delta = p.targets[t].positions;
    if (delta.size() != vertexCount) continue;
    for (size_t n = 0; n < nodeCount; ++n) posed[n] = rest[n] + delta[s.firstVertex[n]];
    const Shape shape = measure(s, posed, normal);
    for (size_t n = 0; n < nodeCount; ++n) {
      if (edge[n] <= 0.0f || restShape.area[n] <= 0.0f) {
        raw[n] = 0.0f;
        continue;
      }
      const float deeper = (shape.depth[n] - restShape.depth[n]) / edge[n];
      const float compressed = 1.0f - shape.area[n] / restShape.area[n];
      const float d = kConcavityGain * std::max(deeper, 0.0f) + kCompressionGain * std::max(compressed, 0.0f);
      raw[n] = std::isfinite(d) ? d : 0.0f;
    }
    // One smoothing pass: a fold is a band, not single speckled vertices.
    for (size_t n = 0; n < nodeCount; ++n) {
      const uint32_t begin = s.ringOffsets[n], end = s.ringOffsets[n + 1];
      float around = 0.0f;
      for (uint32_t r = begin; r < end; ++r) around += raw[s.ring[r]];
      const float smooth = end > begin ? 0.5f * raw[n] + 0.5f * around / float(end - begin) : raw[n];
      smoothed[n] = smooth < kThreshold ? 0.0f : std::min(smooth, 1.0f);
    }
    if (std::all_of(smoothed.begin(), smoothed.end(), [](float d) { return d == 0.0f; })) continue;
    std::vector<float>& out = darkening[t];
    out.resize(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) out[v] = smoothed[s.nodeOf[v]];
  }
  return darkening;
}

bool hasCreases(const std::vector<std::vector<float>>& darkening) {
  // Kept targets hold a value of at least kThreshold somewhere.
  return std::any_of(darkening.begin(), darkening.end(), [](const std::vector<float>& d) { return !d.empty(); });
}

}  // namespace eng
