#include "autorig/mouth_opening.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <span>
#include <unordered_map>
#include <utility>

#include "autorig/carried_pieces.h"
#include "autorig/dense_correspondence.h"
#include "autorig/face_frame.h"
#include "autorig/landmark_warp.h"
#include "autorig/skin_in_front.h"
#include "engine/scene/inner_face_parts.h"
#include "engine/scene/ray_triangle.h"

namespace autorig {
namespace {

// The mouth's box where the lips are told apart, in eye spans: above and
// below the lip line, behind the lips' middle, and past the corners.
constexpr float kMouthBoxHeight = 0.2f;
constexpr float kMouthBoxDepth = 0.12f;
// Vertices this far above (below) the lip line are the upper (lower) lip,
// for telling the lips of a welded mouth apart.
constexpr float kLipSeed = 0.05f;
// Whether lips are welded is asked of the skin at each lip's outer border in
// the middle (landmarks 50-52, 56-58): the vertex nearest each point and those
// within half the way to the lip's inner point (at most this many eye spans).
// Heights off the lip line misled: the line is where dlib sees the lips meet,
// and a lip's rim can reach far across it (Ready Player Me's lips seen parted
// under a moustache, the upper lip's rim curling in 0.05 eye span below it;
// the built-in head's lower lip, its rim 0.04 above, the upper lip 0.04 thick).
constexpr float kBorderSeed = 0.04f;
// Fewer seam vertices than this are no welded mouth.
constexpr size_t kMinSeamVertices = 3;
// Lips welded along more than one line are cut line by line, each cut's seam
// left out of the next one's search, until they no longer join between the
// corners: an STL welds every pair of coincident corners, so a game head's
// closed lips come welded at their outer contact and again at their inner
// rims, where the mouth's inside meets them. One cut (along the deeper line)
// left the outer contact joined: a sheet of lip across the opening.
constexpr int kCutPasses = 3;

struct MouthBox {
  glm::vec3 lipCentre{0.0f};
  float left = 0.0f, right = 0.0f;  // the corners across the midline, eye spans
  float margin = 0.0f;              // past (or within) the corners, eye spans
  glm::vec3 corners[2]{};           // landmarks 48 and 54
  // Landmarks 50-52 and 56-58, each with how far about it is surely its lip.
  std::array<std::pair<glm::vec3, float>, 3> upperBorder{}, lowerBorder{};
};

// Where welded lips meet: the cheapest way along the skin's edges from one
// mouth corner to the other, an edge costing its length, less where it runs
// recessed behind the lips' front (the crease between closed lips) and more
// away from the lip line. A path by distance alone (or lips told apart by
// which side's seeds are nearer) wanders a row or two off the crease: a strip
// of one lip then stays with the other and the opening has steps.
constexpr float kCreasePull = 4.0f;     // per radius of recess: half a radius behind costs e^-2
constexpr float kCreaseRadius = 0.05f;  // eye spans: the skin about a vertex its recess is measured against
constexpr float kLipLineBand = 0.06f;   // eye spans off the lip line where the cost has doubled

struct MouthGraph {
  std::vector<char> inMouth;                    // the vertex is skin in the mouth's box
  std::vector<std::vector<uint32_t>> neighbours;  // edges within the box
  float typicalEdge = 0.0f;                     // their median length, world units
};

MouthGraph mouthGraph(const eng::Primitive& prim, const std::vector<glm::vec3>& world, const std::vector<FacePart>& parts,
                      const std::vector<char>& leftOut, const LandmarkFrame& frame, const MouthBox& box) {
  const size_t n = world.size();
  MouthGraph g;
  g.inMouth.assign(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (parts[v] != FacePart::Skin || leftOut[v]) continue;
    const float side = frame.sideOf(world[v]), above = frame.aboveLipLine(world[v]);
    const float depth = glm::dot(world[v] - box.lipCentre, frame.forward()) / frame.eyeSpan();
    g.inMouth[v] = side > box.left - box.margin && side < box.right + box.margin && std::abs(above) < kMouthBoxHeight &&
                   depth > -kMouthBoxDepth;
  }
  g.neighbours.resize(n);
  std::vector<float> lengths;
  for (size_t t = 0; t + 2 < prim.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = prim.indices[t + size_t(k)], b = prim.indices[t + size_t((k + 1) % 3)];
      if (a >= n || b >= n || !g.inMouth[a] || !g.inMouth[b]) continue;
      g.neighbours[a].push_back(b);
      g.neighbours[b].push_back(a);
      lengths.push_back(glm::distance(world[a], world[b]));
    }
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2), lengths.end());
    g.typicalEdge = lengths[lengths.size() / 2];
  }
  return g;
}

using Entry = std::pair<float, uint32_t>;
using Front = std::priority_queue<Entry, std::vector<Entry>, std::greater<>>;

// Distances along the box's edges from the seeds, never through a barrier
// vertex; an edge costs its length times the mean `weight` of its ends (none:
// 1). `previous` (optional) receives each vertex's step back towards a seed.
std::vector<float> distancesFrom(const std::vector<glm::vec3>& world, const MouthGraph& g, const std::vector<char>& seeds,
                                 const std::vector<char>& barrier, const std::vector<float>* weight = nullptr,
                                 std::vector<uint32_t>* previous = nullptr) {
  std::vector<float> distance(world.size(), std::numeric_limits<float>::infinity());
  if (previous) previous->assign(world.size(), uint32_t(world.size()));
  Front queue;
  for (size_t v = 0; v < world.size(); ++v)
    if (seeds[v] && !barrier[v]) distance[v] = 0.0f, queue.push({0.0f, uint32_t(v)});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (uint32_t w : g.neighbours[v]) {
      const float cost = weight ? 0.5f * ((*weight)[v] + (*weight)[w]) : 1.0f;
      const float through = d + glm::distance(world[v], world[w]) * cost;
      if (barrier[w] || !(through < distance[w])) continue;
      distance[w] = through, queue.push({through, w});
      if (previous) (*previous)[w] = v;
    }
  }
  return distance;
}

// The crease's vertices, corner to corner (empty when the corners are not joined in the box).
std::vector<char> creasePath(const std::vector<glm::vec3>& world, const MouthGraph& g, const LandmarkFrame& frame,
                             const MouthBox& box) {
  const size_t n = world.size();
  std::vector<char> onPath(n, 0);
  // How far each vertex lies behind the mean of the skin within the radius
  // about it, over the radius: < 0 in a crease, about 0 on a plane or a slope.
  const float radius = kCreaseRadius * frame.eyeSpan();
  auto depthOf = [&](size_t v) { return glm::dot(world[v], frame.forward()); };
  std::unordered_map<int64_t, std::vector<uint32_t>> cells;
  auto cellKey = [&](const glm::ivec3& c) { return (int64_t(c.x) * 73856093) ^ (int64_t(c.y) * 19349663) ^ (int64_t(c.z) * 83492791); };
  auto cellOf = [&](const glm::vec3& q) { return glm::ivec3(glm::floor(q / radius)); };
  for (size_t v = 0; v < n; ++v)
    if (g.inMouth[v]) cells[cellKey(cellOf(world[v]))].push_back(uint32_t(v));
  std::vector<float> weight(n, 1.0f);
  for (size_t v = 0; v < n; ++v) {
    if (!g.inMouth[v]) continue;
    const glm::ivec3 c = cellOf(world[v]);
    float sum = 0.0f;
    int count = 0;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z) {
          const auto found = cells.find(cellKey(c + glm::ivec3(x, y, z)));
          if (found == cells.end()) continue;
          for (uint32_t w : found->second)
            if (glm::distance(world[w], world[v]) < radius) sum += depthOf(w), ++count;
        }
    const float recess = (depthOf(v) - sum / float(count)) / radius;
    const float off = frame.aboveLipLine(world[v]) / kLipLineBand;
    weight[v] = std::exp(kCreasePull * recess) * (1.0f + off * off);
  }
  // Of the box's vertices with an edge in it: a vertex no triangle uses
  // (a welded copy left behind) can lie on a corner.
  auto nearest = [&](const glm::vec3& p) {
    uint32_t best = uint32_t(n);
    float bestDistance = std::numeric_limits<float>::max();
    for (size_t v = 0; v < n; ++v)
      if (g.inMouth[v] && !g.neighbours[v].empty() && glm::distance(world[v], p) < bestDistance)
        bestDistance = glm::distance(world[v], p), best = uint32_t(v);
    return best;
  };
  const uint32_t from = nearest(box.corners[0]), to = nearest(box.corners[1]);
  if (from == n || to == n || from == to) return onPath;
  std::vector<char> seed(n, 0);
  seed[from] = 1;
  std::vector<uint32_t> previous;
  const std::vector<float> cost = distancesFrom(world, g, seed, std::vector<char>(n, 0), &weight, &previous);
  if (!std::isfinite(cost[to])) return onPath;
  for (uint32_t v = to; v != n; v = previous[v]) onPath[v] = 1;
  return onPath;
}


// The vertices of the box clearly above (sign 1) or below (-1) the lip line.
std::vector<char> lipSeeds(const std::vector<glm::vec3>& world, const MouthGraph& g, const LandmarkFrame& frame, float sign) {
  std::vector<char> seeds(world.size(), 0);
  for (size_t v = 0; v < world.size(); ++v) seeds[v] = g.inMouth[v] && sign * frame.aboveLipLine(world[v]) > kLipSeed;
  return seeds;
}

// The vertices of the box at a point of a lip's outer border: within its
// reach, or nearest it (a coarse mesh's vertices lie further apart) when
// within kBorderSeed or one and a half of the box's edges.
std::vector<char> atTheBorder(const std::vector<glm::vec3>& world, const MouthGraph& g, const LandmarkFrame& frame,
                              const std::pair<glm::vec3, float>& border) {
  const auto& [point, reach] = border;
  std::vector<char> seeds(world.size(), 0);
  size_t nearest = world.size();
  float nearestDistance = std::max(kBorderSeed * frame.eyeSpan(), 1.5f * g.typicalEdge);
  for (size_t v = 0; v < world.size(); ++v) {
    if (!g.inMouth[v]) continue;
    const float d = glm::distance(world[v], point);
    if (d < reach) seeds[v] = 1;
    if (d < nearestDistance) nearestDistance = d, nearest = v;
  }
  if (nearest < world.size()) seeds[nearest] = 1;
  return seeds;
}

// Welded lips are one surface between the corners: the upper lip's outer
// border reaches the lower's without leaving the mouth's middle half.
// Separate lips (and a mouth's inside, whose back lies behind the box) join
// only round the corners, and facecap's inside its corners, at 0.74 of the
// half-width off the middle. Two of the three points of each border must
// reach each other: one landmark can lie on the other lip (the built-in
// head's upper lip is 0.04 eye span thick).
bool lipsJoinedBetweenTheCorners(const std::vector<glm::vec3>& world, const MouthGraph& g, const LandmarkFrame& frame,
                                 const MouthBox& box) {
  const float middle = 0.5f * (box.left + box.right), half = 0.5f * (box.right - box.left);
  std::vector<char> offTheMiddle(world.size(), 0);
  for (size_t v = 0; v < world.size(); ++v) offTheMiddle[v] = std::abs(frame.sideOf(world[v]) - middle) > 0.5f * half;
  std::vector<std::vector<char>> lower;
  for (const auto& point : box.lowerBorder) lower.push_back(atTheBorder(world, g, frame, point));
  int joined = 0;
  for (const auto& point : box.upperBorder) {
    const std::vector<float> fromUpper = distancesFrom(world, g, atTheBorder(world, g, frame, point), offTheMiddle);
    const auto reached = std::count_if(lower.begin(), lower.end(), [&](const std::vector<char>& seeds) {
      for (size_t v = 0; v < world.size(); ++v)
        if (seeds[v] && std::isfinite(fromUpper[v])) return true;
      return false;
    });
    joined += reached >= 2;
  }
  return joined >= 2;
}

// Each vertex of the mouth's box labelled lower lip or not: nearer, along the
// edges and never through the crease, to the vertices clearly below the lip
// line than to those clearly above it.
std::vector<char> lowerLip(const std::vector<glm::vec3>& world, const MouthGraph& g, const std::vector<char>& crease,
                           const LandmarkFrame& frame) {
  const std::vector<float> toUpper = distancesFrom(world, g, lipSeeds(world, g, frame, 1.0f), crease);
  const std::vector<float> toLower = distancesFrom(world, g, lipSeeds(world, g, frame, -1.0f), crease);
  std::vector<char> lower(world.size(), 0);
  for (size_t v = 0; v < world.size(); ++v) lower[v] = g.inMouth[v] && !crease[v] && toLower[v] < toUpper[v];
  return lower;
}

// The primitive's vertices at rest (world space) with their parts, and those
// a cut leaves out of its search: the seams cut so far (a seam vertex and its
// copy) and, after the first cut, the skin hidden behind the lips.
struct CutSurface {
  std::vector<glm::vec3> world;
  std::vector<FacePart> parts;
  std::vector<char> leftOut;
};

// Later cuts run where the lips meet in sight: the first may have taken a
// line inside the mouth (the deeper one), which leaves the front joined.
// Marks the skin about the mouth that other skin hides from the front.
void leaveOutTheHiddenSkin(const eng::Primitive& prim, CutSurface& surface, const LandmarkFrame& frame, const MouthBox& box) {
  const float mouthWidth = glm::distance(box.corners[0], box.corners[1]);
  SkinInFront skin(frame, 0.05f * mouthWidth);
  for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
    const uint32_t* tri = &prim.indices[t];
    if (std::max({tri[0], tri[1], tri[2]}) >= surface.world.size()) continue;
    if (glm::distance(surface.world[tri[0]], box.lipCentre) > 1.5f * mouthWidth) continue;
    skin.add(surface.world[tri[0]], surface.world[tri[1]], surface.world[tri[2]]);
  }
  for (size_t v = 0; v < surface.world.size(); ++v)
    if (glm::distance(surface.world[v], box.lipCentre) < mouthWidth &&
        skin.covers(surface.world[v] + 0.02f * mouthWidth * frame.forward()))
      surface.leftOut[v] = 1;
}

// Cuts the welded lips of one primitive along their crease; returns how many
// seam vertices got a copy (`surface` grows by them).
size_t cutWeldedLips(eng::Primitive& prim, CutSurface& surface, const LandmarkFrame& frame, const MouthBox& box) {
  const std::vector<glm::vec3>& world = surface.world;
  const std::vector<FacePart>& parts = surface.parts;
  const size_t n = world.size();
  if (n != prim.vertexCount() || parts.size() != n) return 0;
  const MouthGraph graph = mouthGraph(prim, world, parts, surface.leftOut, frame, box);
  if (!lipsJoinedBetweenTheCorners(world, graph, frame, box)) return 0;
  const std::vector<char> crease = creasePath(world, graph, frame, box);
  const std::vector<char> lower = lowerLip(world, graph, crease, frame);
  // The seam: crease vertices between the corners with the upper lip on one
  // side and the lower on the other (separate lips' crease runs along one
  // lip's rim). Each gets a copy for the triangles that reach the lower lip;
  // past the corners the lips stay joined.
  std::vector<char> touchesUpper(n, 0), touchesLower(n, 0);
  const size_t triangles = prim.indices.size() / 3;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* i = &prim.indices[t * 3];
    if (i[0] >= n || i[1] >= n || i[2] >= n) continue;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        if (!crease[i[a]] || a == b || crease[i[b]] || !graph.inMouth[i[b]]) continue;
        (lower[i[b]] ? touchesLower : touchesUpper)[i[a]] = 1;
      }
  }
  std::vector<char> seam(n, 0);
  for (size_t v = 0; v < n; ++v) {
    const float side = frame.sideOf(world[v]);
    seam[v] = touchesUpper[v] && touchesLower[v] && side > box.left && side < box.right;
  }
  if (size_t(std::count(seam.begin(), seam.end(), 1)) < kMinSeamVertices) return 0;
  std::vector<uint32_t> copyOf(n, std::numeric_limits<uint32_t>::max());
  size_t cut = 0;
  for (size_t t = 0; t < triangles; ++t) {
    uint32_t* i = &prim.indices[t * 3];
    if (i[0] >= n || i[1] >= n || i[2] >= n || !(lower[i[0]] || lower[i[1]] || lower[i[2]])) continue;
    for (int k = 0; k < 3; ++k) {
      if (!seam[i[k]]) continue;
      if (copyOf[i[k]] == std::numeric_limits<uint32_t>::max()) {
        copyOf[i[k]] = appendVertexOf(prim, prim, i[k]);
        ++cut;
      }
      i[k] = copyOf[i[k]];
    }
  }
  for (size_t v = 0; v < n; ++v) {
    if (copyOf[v] == std::numeric_limits<uint32_t>::max()) continue;
    surface.world.push_back(world[v]);
    surface.parts.push_back(parts[v]);
    surface.leftOut.push_back(1);
    surface.leftOut[v] = 1;
  }
  return cut;
}

// How far back (along the face's forward, in steps of kTuckStep mouth widths)
// `points` must move, all together, to lie behind the skin; -1 when no move
// up to kTuckSteps hides them. Every `stride`-th point is tried.
constexpr float kTuckStep = 0.05f;
constexpr int kTuckSteps = 12;
int stepsBehindTheSkin(std::span<const glm::vec3> points, size_t stride, const SkinInFront& skin,
                       const LandmarkFrame& frame, float mouthWidth) {
  for (int step = 0; step <= kTuckSteps; ++step) {
    const glm::vec3 back = frame.forward() * (-kTuckStep * mouthWidth * float(step));
    bool hidden = true;
    for (size_t v = 0; v < points.size() && hidden; v += stride) hidden = skin.covers(points[v] + back);
    if (hidden) return step;
  }
  return -1;
}

// The face's skin primitive the inside of the mouth joins (the one nearest
// the lips), the vertex whose motion it shares (nearest the nose's base:
// above the mouth, with the head, not the jaw), and the skin about the mouth.
struct MouthHost {
  size_t primitive = 0;  // into PosedFace::primitives
  uint32_t anchor = 0;
  SkinInFront skin;
};

std::optional<MouthHost> findMouthHost(const eng::Model& face, const PosedFace& posed, const FaceParts& parts,
                                       const FaceLandmarks& landmarks, const glm::vec3& lipCentre, float mouthWidth) {
  MouthHost host{posed.primitives.size(), 0, SkinInFront(LandmarkFrame(landmarks), 0.05f * mouthWidth)};
  float nearest = std::numeric_limits<float>::max();
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    const eng::Primitive& prim = face.meshes[pp.mesh].primitives[pp.primitive];
    for (size_t v = 0; v < pp.positions.size(); ++v)
      if (parts.vertexParts[i][v] == FacePart::Skin && glm::distance(pp.positions[v], lipCentre) < nearest)
        nearest = glm::distance(pp.positions[v], lipCentre), host.primitive = i;
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      const uint32_t* tri = &prim.indices[t];
      if (tri[0] >= pp.positions.size() || tri[1] >= pp.positions.size() || tri[2] >= pp.positions.size()) continue;
      if (parts.vertexParts[i][tri[0]] != FacePart::Skin) continue;
      if (glm::distance(pp.positions[tri[0]], lipCentre) > 2.0f * mouthWidth) continue;
      host.skin.add(pp.positions[tri[0]], pp.positions[tri[1]], pp.positions[tri[2]]);
    }
  }
  if (host.primitive == posed.primitives.size()) return std::nullopt;
  const PosedPrimitive& pp = posed.primitives[host.primitive];
  nearest = std::numeric_limits<float>::max();
  for (size_t v = 0; v < pp.positions.size(); ++v)
    if (parts.vertexParts[host.primitive][v] == FacePart::Skin && glm::distance(pp.positions[v], landmarks.points[33]) < nearest)
      nearest = glm::distance(pp.positions[v], landmarks.points[33]), host.anchor = uint32_t(v);
  return host;
}

// The source's inside of the mouth: its mouth's inside, teeth and tongue
// (by their names, eng::partsInsideTheHead), not its eyeballs.
std::vector<size_t> insideOfTheMouth(const SourceFace& source) {
  const std::vector<std::vector<bool>> inside = eng::partsInsideTheHead(*source.model);
  std::vector<size_t> picked;
  for (size_t i = 0; i < source.posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = source.posed.primitives[i];
    if (pp.mesh >= inside.size() || pp.primitive >= inside[pp.mesh].size() || !inside[pp.mesh][pp.primitive]) continue;
    const std::vector<FacePart>& parts = source.parts.vertexParts[i];
    const bool eyeball = std::any_of(parts.begin(), parts.end(),
                                     [](FacePart p) { return p == FacePart::EyeballLeft || p == FacePart::EyeballRight; });
    if (!eyeball) picked.push_back(i);
  }
  return picked;
}

// The source's inside of the mouth carried into the face by the landmark
// warp, as primitives of the skin's mesh; the vertex count added, or 0 with a note why not.
size_t transplantTheInsideOfTheMouth(eng::Model& face, const PosedFace& posed, const FaceParts& parts,
                                     const FaceLandmarks& landmarks, const LandmarkFrame& frame, const SourceFace& source,
                                     std::vector<std::string>& notes) {
  const auto& p = landmarks.points;
  glm::vec3 lipCentre(0.0f);
  for (size_t i = 60; i < 68; ++i) lipCentre += p[i] / 8.0f;
  const float mouthWidth = glm::length(p[54] - p[48]);
  const std::optional<MouthHost> host = findMouthHost(face, posed, parts, landmarks, lipCentre, mouthWidth);
  const std::vector<size_t> pieces = insideOfTheMouth(source);
  if (!host || pieces.empty() || source.model == nullptr) return 0;
  const LandmarkPairs pairs = distinctLandmarkPairs(source.landmarks, landmarks);
  eng::Result<LandmarkWarp> warp = LandmarkWarp::build(pairs.source, pairs.target, pairs.minSeparation);
  const PosedPrimitive& hostPosed = posed.primitives[host->primitive];
  const std::string label = meshLabel(face, hostPosed.mesh);
  if (!warp) {
    notes.push_back(label + ": nothing inside the mouth, and the built-in head's could not be carried over (" +
                    warp.error().message + ")");
    return 0;
  }
  // Each piece warped into the face; teeth and tongue then moved back as one
  // until the closed lips and the skin hide them, the mouth's inside vertex
  // by vertex beside the lips (the face may curve back there sooner than the
  // head does).
  struct Piece {
    size_t source;
    std::vector<glm::vec3> world;
  };
  std::vector<Piece> carried;
  for (size_t i : pieces) {
    Piece piece{i, {}};
    for (const glm::vec3& q : source.posed.primitives[i].positions) piece.world.push_back(warp->apply(q));
    const eng::Primitive& from = source.model->meshes[source.posed.primitives[i].mesh].primitives[source.posed.primitives[i].primitive];
    const bool rigid = std::any_of(source.parts.vertexParts[i].begin(), source.parts.vertexParts[i].end(), [](FacePart q) {
      return q == FacePart::UpperTeeth || q == FacePart::LowerTeeth || q == FacePart::Tongue;
    });
    if (rigid) {
      const int steps = stepsBehindTheSkin(piece.world, 4, host->skin, frame, mouthWidth);
      if (steps < 0) {
        notes.push_back(label + ": nothing inside the mouth, and no room behind its lips for the built-in head's (" +
                        std::to_string(from.vertexCount()) + "-vertex piece left out)");
        continue;
      }
      for (glm::vec3& q : piece.world) q -= frame.forward() * (kTuckStep * mouthWidth * float(steps));
    } else {
      for (glm::vec3& q : piece.world) {
        const glm::vec3 d = q - lipCentre;
        const float x = glm::dot(d, frame.side()) / (0.5f * mouthWidth), y = glm::dot(d, frame.up()) / (0.15f * mouthWidth);
        if (x * x + y * y <= 1.0f) continue;  // seen only through the opening
        const int steps = stepsBehindTheSkin(std::span<const glm::vec3>(&q, 1), 1, host->skin, frame, mouthWidth);
        if (steps > 0) q -= frame.forward() * (kTuckStep * mouthWidth * float(steps));
      }
    }
    carried.push_back(std::move(piece));
  }
  if (carried.empty()) return 0;

  CarriedPieces carrier(face, hostPosed, host->anchor);
  size_t added = 0;
  for (const Piece& piece : carried) added += carrier.add(source, piece.source, piece.world, warp->similarity().rotation);
  notes.push_back(label + ": nothing inside the mouth (no teeth, no tongue): the built-in head's mouth, teeth and tongue "
                  "carried in behind the lips (" + std::to_string(added) + " vertices)");
  return added;
}

}  // namespace

MouthOpening openTheMouth(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks, const FaceParts& parts,
                          const SourceFace& source) {
  MouthOpening opening;
  if (parts.vertexParts.size() != posed.primitives.size()) return opening;
  const LandmarkFrame frame(landmarks);
  const auto& p = landmarks.points;
  MouthBox box;
  for (size_t i = 60; i < 68; ++i) box.lipCentre += p[i] / 8.0f;
  box.left = std::min(frame.sideOf(p[48]), frame.sideOf(p[54]));
  box.right = std::max(frame.sideOf(p[48]), frame.sideOf(p[54]));
  box.margin = 0.08f * (box.right - box.left);
  box.corners[0] = p[48];
  box.corners[1] = p[54];
  auto border = [&](size_t outer, size_t inner) {
    return std::pair{p[outer], std::min(kBorderSeed * frame.eyeSpan(), 0.5f * glm::distance(p[outer], p[inner]))};
  };
  box.upperBorder = {border(50, 61), border(51, 62), border(52, 63)};
  box.lowerBorder = {border(58, 67), border(57, 66), border(56, 65)};
  bool hasInside = false;
  for (const std::vector<FacePart>& vertexParts : parts.vertexParts)
    for (FacePart part : vertexParts)
      hasInside |= part == FacePart::UpperTeeth || part == FacePart::LowerTeeth || part == FacePart::Tongue;
  // Carried in from the face before the cut (the cut moves nothing).
  if (!hasInside) opening.insideVertices = transplantTheInsideOfTheMouth(face, posed, parts, landmarks, frame, source, opening.notes);
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    CutSurface surface{pp.positions, parts.vertexParts[i], std::vector<char>(pp.positions.size(), 0)};
    size_t cut = 0;
    for (int pass = 0; pass < kCutPasses; ++pass) {
      if (pass == 1) leaveOutTheHiddenSkin(face.meshes[pp.mesh].primitives[pp.primitive], surface, frame, box);
      const size_t made = cutWeldedLips(face.meshes[pp.mesh].primitives[pp.primitive], surface, frame, box);
      if (made == 0) break;
      cut += made;
    }
    if (cut == 0) continue;
    opening.cutVertices += cut;
    opening.notes.push_back(meshLabel(face, pp.mesh) + ": lips welded along " + std::to_string(cut) +
                            " vertices, cut between the mouth corners");
  }
  return opening;
}

}  // namespace autorig
