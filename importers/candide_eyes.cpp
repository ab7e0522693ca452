#include "importers/candide_eyes.h"

#include "engine/scene/edge_key.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

namespace importers {
namespace {

struct Topology {
  std::unordered_set<uint64_t> edges;
  std::unordered_map<uint64_t, std::vector<uint32_t>> trianglesOfEdge;
  std::vector<std::vector<uint32_t>> neighbours;  // per vertex
};

Topology topologyOf(size_t vertexCount, std::span<const uint32_t> indices) {
  Topology t;
  t.neighbours.resize(vertexCount);
  for (size_t f = 0; f * 3 + 2 < indices.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[f * 3 + k], b = indices[f * 3 + (k + 1) % 3];
      if (t.edges.insert(eng::undirectedEdgeKey(a, b)).second) {
        t.neighbours[a].push_back(b);
        t.neighbours[b].push_back(a);
      }
      t.trianglesOfEdge[eng::undirectedEdgeKey(a, b)].push_back(uint32_t(f));
    }
  return t;
}

enum class Margin : uint8_t { None, Upper, Lower };

// A lid margin is a handful of vertices (CANDIDE-3: three per lid); more means
// the unit is not a blink, and the search below would grow with its square.
constexpr size_t kMaxMarginVertices = 64;

// The lid margins of one eye as a closed loop of mesh edges, or empty: the
// corners are the vertices (not on a margin) next to both margins, innermost
// and outermost; each margin runs from the inner corner outward.
std::vector<uint32_t> lidLoop(std::span<const glm::vec3> positions, const Topology& topology,
                              std::span<const Margin> margin, std::vector<uint32_t> upper, std::vector<uint32_t> lower,
                              bool left) {
  if (upper.empty() || lower.empty() || upper.size() + lower.size() > kMaxMarginVertices) return {};
  auto fromMidline = [&](uint32_t v) { return std::abs(positions[v].x); };
  std::vector<uint32_t> corners;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    if ((positions[v].x > 0.0f) != left || margin[v] != Margin::None) continue;
    bool nextToUpper = false, nextToLower = false;
    for (uint32_t w : topology.neighbours[v]) {
      nextToUpper = nextToUpper || margin[w] == Margin::Upper;
      nextToLower = nextToLower || margin[w] == Margin::Lower;
    }
    if (nextToUpper && nextToLower) corners.push_back(v);
  }
  if (corners.size() < 2) return {};
  auto byMidline = [&](uint32_t a, uint32_t b) { return fromMidline(a) < fromMidline(b); };
  const uint32_t inner = *std::min_element(corners.begin(), corners.end(), byMidline);
  const uint32_t outer = *std::max_element(corners.begin(), corners.end(), byMidline);
  std::sort(upper.begin(), upper.end(), byMidline);
  std::sort(lower.begin(), lower.end(), byMidline);
  if (fromMidline(inner) >= fromMidline(upper.front()) || fromMidline(outer) <= fromMidline(upper.back()) ||
      fromMidline(inner) >= fromMidline(lower.front()) || fromMidline(outer) <= fromMidline(lower.back()))
    return {};
  std::vector<uint32_t> loop{inner};
  loop.insert(loop.end(), upper.begin(), upper.end());
  loop.push_back(outer);
  loop.insert(loop.end(), lower.rbegin(), lower.rend());
  for (size_t i = 0; i < loop.size(); ++i)
    if (!topology.edges.count(eng::undirectedEdgeKey(loop[i], loop[(i + 1) % loop.size()]))) return {};
  return loop;
}

glm::vec2 rimCentre(std::span<const glm::vec3> positions, const std::vector<uint32_t>& rim) {
  glm::vec2 c(0.0f);
  for (uint32_t v : rim) c += glm::vec2(positions[v]);
  return c / float(rim.size());
}

float rimWidth(std::span<const glm::vec3> positions, const std::vector<uint32_t>& rim) {
  float width = 0.0f;
  for (uint32_t a : rim)
    for (uint32_t b : rim) width = std::max(width, glm::length(glm::vec2(positions[a]) - glm::vec2(positions[b])));
  return width;
}

// Whether the front projection of triangle abc contains p (either winding).
bool containsXY(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, glm::vec2 p) {
  auto side = [&](const glm::vec3& u, const glm::vec3& v) { return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x); };
  const float d1 = side(a, b), d2 = side(b, c), d3 = side(c, a);
  return !((d1 < 0.0f || d2 < 0.0f || d3 < 0.0f) && (d1 > 0.0f || d2 > 0.0f || d3 > 0.0f));
}

// The triangles enclosed by `rim`: flooded from the front-most triangle under
// the rim's centre across every edge that is not the rim's. Empty when the
// flood is not a small patch near the rim (the loop does not enclose it).
std::vector<uint32_t> enclosedTriangles(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                        const Topology& topology, const std::vector<uint32_t>& rim) {
  const glm::vec2 centre = rimCentre(positions, rim);
  const float width = rimWidth(positions, rim);
  const size_t triangles = indices.size() / 3;
  int64_t seed = -1;
  float seedDepth = -INFINITY;
  for (size_t f = 0; f < triangles; ++f) {
    const glm::vec3 &a = positions[indices[f * 3]], &b = positions[indices[f * 3 + 1]], &c = positions[indices[f * 3 + 2]];
    const float depth = (a.z + b.z + c.z) / 3.0f;
    if (depth > seedDepth && containsXY(a, b, c, centre)) seed = int64_t(f), seedDepth = depth;
  }
  if (seed < 0) return {};
  std::unordered_set<uint64_t> rimEdges;
  for (size_t i = 0; i < rim.size(); ++i) rimEdges.insert(eng::undirectedEdgeKey(rim[i], rim[(i + 1) % rim.size()]));
  std::vector<uint32_t> inside{uint32_t(seed)};
  std::unordered_set<uint32_t> seen{uint32_t(seed)};
  for (size_t next = 0; next < inside.size(); ++next) {
    const uint32_t f = inside[next];
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[f * 3 + k], b = indices[f * 3 + (k + 1) % 3];
      if (glm::length(glm::vec2(positions[a]) - centre) > width) return {};  // leaked out of the eye
      if (rimEdges.count(eng::undirectedEdgeKey(a, b))) continue;
      for (uint32_t g : topology.trianglesOfEdge.at(eng::undirectedEdgeKey(a, b)))
        if (seen.insert(g).second) inside.push_back(g);
    }
    if (inside.size() > triangles / 8) return {};
  }
  return inside;
}

}  // namespace

std::vector<MaskEyeOpening> cutEyeOpenings(std::span<const glm::vec3> positions, std::vector<uint32_t>& indices,
                                       std::span<const glm::vec3> eyesClosed) {
  if (eyesClosed.size() != positions.size()) return {};
  const Topology topology = topologyOf(positions.size(), indices);
  std::vector<MaskEyeOpening> openings;
  std::vector<bool> cut(indices.size() / 3, false);
  std::vector<Margin> margin(positions.size(), Margin::None);
  for (size_t v = 0; v < positions.size(); ++v)
    if (eyesClosed[v].y != 0.0f) margin[v] = eyesClosed[v].y < 0.0f ? Margin::Upper : Margin::Lower;
  for (bool left : {true, false}) {
    std::vector<uint32_t> upper, lower;
    for (uint32_t v = 0; v < positions.size(); ++v)
      if ((positions[v].x > 0.0f) == left && margin[v] != Margin::None)
        (margin[v] == Margin::Upper ? upper : lower).push_back(v);
    MaskEyeOpening opening{left, lidLoop(positions, topology, margin, upper, lower, left)};
    if (opening.rim.empty()) continue;
    const std::vector<uint32_t> inside = enclosedTriangles(positions, indices, topology, opening.rim);
    if (inside.empty()) continue;
    for (uint32_t f : inside) cut[f] = true;
    openings.push_back(std::move(opening));
  }
  std::vector<uint32_t> kept;
  kept.reserve(indices.size());
  for (size_t f = 0; f < cut.size(); ++f)
    if (!cut[f]) kept.insert(kept.end(), indices.begin() + f * 3, indices.begin() + f * 3 + 3);
  indices = std::move(kept);
  return openings;
}

eng::Primitive eyeballBehind(std::span<const glm::vec3> positions, const MaskEyeOpening& opening) {
  const glm::vec2 centre = rimCentre(positions, opening.rim);
  // A real eyeball is about as wide as the opening; a little wider here so
  // its disc covers the corners, which CANDIDE sets well behind the lids.
  const float radius = 0.55f * rimWidth(positions, opening.rim);
  float z = INFINITY;
  for (uint32_t v : opening.rim) {
    const float d = glm::length(glm::vec2(positions[v]) - centre);
    z = std::min(z, positions[v].z - std::sqrt(std::max(radius * radius - d * d, 0.0f)));
  }
  const glm::vec3 c(centre, z - 0.02f * radius);
  constexpr int kRings = 24, kSegments = 48;
  eng::Primitive ball;
  for (int i = 0; i <= kRings; ++i) {
    const float theta = std::numbers::pi_v<float> * float(i) / kRings;  // from +y
    for (int j = 0; j <= kSegments; ++j) {
      const float phi = 2.0f * std::numbers::pi_v<float> * float(j) / kSegments;  // 0 looks along +z
      const glm::vec3 dir(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      ball.positions.push_back(c + radius * dir);
      ball.normals.push_back(dir);
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      const uint32_t a = uint32_t(i * (kSegments + 1) + j), b = a + kSegments + 1;
      if (i > 0) ball.indices.insert(ball.indices.end(), {a, b, a + 1});               // none at the top pole
      if (i < kRings - 1) ball.indices.insert(ball.indices.end(), {a + 1, b, b + 1});  // none at the bottom pole
    }
  return ball;
}

eng::MorphTarget eyeballFollowing(std::span<const glm::vec3> positions, const MaskEyeOpening& opening,
                                  const eng::Primitive& ball, std::span<const glm::vec3> deltas) {
  std::vector<glm::vec3> moved(positions.begin(), positions.end());
  glm::vec3 shift(0.0f);
  for (uint32_t v : opening.rim) {
    moved[v] += deltas[v];
    shift += deltas[v] / float(opening.rim.size());
  }
  auto growth = [](float before, float after) { return before > 0.0f ? after / before - 1.0f : 0.0f; };
  // The ball's size follows the opening's widest span, as eyeballBehind sized it.
  const float s = growth(rimWidth(positions, opening.rim), rimWidth(moved, opening.rim));
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : ball.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = 0.5f * (hi.x - lo.x);
  eng::MorphTarget target;
  target.positions.reserve(ball.positions.size());
  // Scaled by 1 + s about the front pole (centre + radius along +z).
  for (const glm::vec3& p : ball.positions) target.positions.push_back(shift + s * (p - centre - glm::vec3(0.0f, 0.0f, radius)));
  target.normals.assign(ball.positions.size(), glm::vec3(0.0f));
  return target;
}

}  // namespace importers
