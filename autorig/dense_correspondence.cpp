#include "autorig/dense_correspondence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "engine/scene/position_hash.h"

namespace autorig {
namespace {

constexpr uint32_t kNotGathered = UINT32_MAX;

// Within this distance of a closing line (eye spans) a vertex's side is the
// mesh's to say: about the lips' and the lids' thickness.
constexpr float kLineBand = 0.06f;
// A rim vertex whose triangles lean up or down by this share of their
// spread is on that lip: the built-in head's lips' rims lean 0.51-0.57, the
// lining's inside its mouth 0.31-0.41 and facecap's few rims at its slit
// 0.30-0.39 (both left to the edges: taken as sure at 0.3, they tore 8 of
// facecap's lip edges in anger).
constexpr float kRimLean = 0.45f;
// The warp passes near, not through, the landmarks (a smoothing spline; the
// weight in the RBF's unit box): dlib's points on a face it does not know are
// often 0.02 eye spans off, and a warp through each of them bends between
// neighbours a millimetre apart, so a unit carried by its Jacobian folds the
// skin about the mouth (through every point, noise of 0.02 eye spans on the
// built-in head's found landmarks folded 2.4 times as many triangles there:
// 227 against 96 over six draws; 0.015 folded more, and at 0.06 facecap's
// made units moved further from its own).
constexpr double kLandmarkSmoothing = 0.03;
// Except the lids' lines and the mouth's corners (passedThrough): the
// source's corners and lid lines must land on the target's, or a unit carries
// the source's corner onto the skin beside the target's (Ready Player Me's
// anger tore 6 edges of the lining in its mouth's corners with only the inner
// lips' middles held, 2 with the corners held too; with the lids smoothed,
// facecap's made eyeWide moved 0.85 of its own's size from it, held 0.76).
// The inner lips' middles are passed near: dlib's points there are often off
// by the lips' own gap, and a warp through them bends across the mouth (the
// built-in head under noise of 0.02 eye spans folded 610 skin triangles about
// the mouth over six draws through them, 454 near them; 218 with the corners
// steadied too, below).
bool passedThrough(size_t landmark) { return onLidLine(landmark) || atMouthCorner(landmark); }

glm::vec3 onSource(const FaceSurface& source, const ClosestPoint& match) {
  const auto& t = source.triangles[match.triangle];
  return match.barycentric.x * source.positions[t[0]] + match.barycentric.y * source.positions[t[1]] +
         match.barycentric.z * source.positions[t[2]];
}

// Well-spread target vertices on the face's front, away from the landmarks
// and the closing lines (the landmarks hold those), each paired with its
// closest point on the warped source, as (source rest point, target point).
void growPairs(const FaceSurface& source, const std::vector<glm::vec3>& warped, const FaceSurface& target,
               const LandmarkFrame& frame, const FaceLandmarks& landmarks, const CorrespondenceOptions& options,
               std::vector<glm::vec3>& sourcePoints, std::vector<glm::vec3>& targetPoints) {
  const TriangleGrid grid(warped, source.triangles, {});
  const std::vector<glm::vec3> normals = vertexNormals(target.positions, target.triangles);
  const float spacing = options.sampleSpacing * frame.eyeSpan();
  const float nearLandmark = 0.5f * spacing;
  std::unordered_set<uint64_t> taken;
  size_t added = 0;
  for (size_t v = 0; v < target.positions.size() && added < size_t(options.maxGrownPairs); ++v) {
    const glm::vec3& p = target.positions[v];
    if (target.parts[v] != FacePart::Skin || frame.region(p) != FaceRegion::None) continue;
    const glm::vec3 local = p - frame.origin();
    // The face's front: within an eye span and a half of its middle, not behind the eyes.
    if (glm::length(local) > 1.5f * frame.eyeSpan() || glm::dot(local, frame.forward()) < -0.3f * frame.eyeSpan()) continue;
    const glm::ivec3 cell = glm::ivec3(glm::floor(local / spacing)) + 1024;
    const uint64_t key = (uint64_t(cell.x) << 42) | (uint64_t(cell.y) << 21) | uint64_t(cell.z);
    if (taken.count(key)) continue;
    bool crowded = false;
    for (const glm::vec3& l : landmarks.points) crowded = crowded || glm::length(l - p) < nearLandmark;
    if (crowded) continue;
    const ClosestPoint match = grid.closest(p, FaceRegion::None, 0.5f * spacing, normals[v]);
    if (!match.found) continue;
    taken.insert(key);
    sourcePoints.push_back(onSource(source, match));
    targetPoints.push_back(p);
    ++added;
  }
}

std::vector<glm::vec3> warpAll(const LandmarkWarp& warp, const std::vector<glm::vec3>& points) {
  std::vector<glm::vec3> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = warp.apply(points[i]);
  return out;
}

}  // namespace

std::vector<char> openingRims(const FaceSurface& surface) {
  std::unordered_map<uint64_t, int> edges;
  for (const auto& t : surface.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = surface.rootOf(t[size_t(k)]), b = surface.rootOf(t[size_t((k + 1) % 3)]);
      if (a != b) ++edges[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)];
    }
  std::vector<char> rim(surface.positions.size(), 0);
  for (const auto& [edge, count] : edges)
    if (count == 1) rim[edge >> 32] = rim[edge & 0xffffffffu] = 1;
  for (size_t v = 0; v < rim.size(); ++v) rim[v] = rim[surface.rootOf(v)];
  return rim;
}

std::vector<FaceRegion> labelRegions(const FaceSurface& surface, const LandmarkFrame& frame) {
  const size_t n = surface.positions.size();
  std::vector<FaceRegion> regions(n, FaceRegion::None);
  std::vector<float> reach(n, std::numeric_limits<float>::infinity());
  using Entry = std::pair<float, uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front;
  std::vector<bool> unsure(n, false);
  // A seam's copies are one point of the surface: labelled once, through the
  // triangles on both sides (else a copy inside the mouth, reached round its
  // corner, takes the other lip from the one on the lip's face).
  for (size_t v = 0; v < n; ++v) {
    if (surface.rootOf(v) != v) continue;
    float margin = 0.0f;
    regions[v] = frame.region(surface.positions[v], &margin);
    if (regions[v] == FaceRegion::None) continue;
    if (margin < kLineBand) {
      unsure[v] = true;
      continue;
    }
    reach[v] = 0.0f;
    front.push({0.0f, uint32_t(v)});
  }
  std::vector<std::vector<uint32_t>> neighbours(n);
  for (const auto& t : surface.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = surface.rootOf(t[size_t(k)]), b = surface.rootOf(t[size_t((k + 1) % 3)]);
      neighbours[a].push_back(b), neighbours[b].push_back(a);
    }
  // A lip's rim where the mouth is slit (its edges of one triangle: the
  // lips apart, or cut where they meet as separate vertices at the same
  // places) lies on the side of the slit its triangles lie on, wherever the
  // landmarks' line runs: a sure vertex of that lip. The line is the
  // landmarks', a few millimetres off the mesh's slit at the corners (the
  // built-in head's lower lip rises 0.03 eye spans above it there), and the
  // lower lip's rim at a corner, reached round it from the upper lip, took
  // the upper lip's motion: a flap stood up at each corner of fear's mouth.
  const std::vector<char> rim = openingRims(surface);
  std::vector<float> lean(n, 0.0f), spread(n, 0.0f);
  for (const auto& t : surface.triangles) {
    const glm::vec3 centroid = (surface.positions[t[0]] + surface.positions[t[1]] + surface.positions[t[2]]) / 3.0f;
    for (uint32_t corner : t) {
      const uint32_t v = surface.rootOf(corner);
      if (!rim[v] || !unsure[v]) continue;
      lean[v] += glm::dot(centroid - surface.positions[v], frame.up());
      spread[v] += glm::length(centroid - surface.positions[v]);
    }
  }
  for (size_t v = 0; v < n; ++v) {
    const bool lip = regions[v] == FaceRegion::UpperLip || regions[v] == FaceRegion::LowerLip;
    if (!lip || !unsure[v] || !rim[v] || !(std::abs(lean[v]) > kRimLean * spread[v])) continue;
    regions[v] = lean[v] > 0.0f ? FaceRegion::UpperLip : FaceRegion::LowerLip;
    unsure[v] = false;
    reach[v] = 0.0f;
    front.push({0.0f, uint32_t(v)});
  }
  // Dijkstra from the sure vertices into the unsure ones along edges.
  while (!front.empty()) {
    const auto [distance, v] = front.top();
    front.pop();
    if (distance > reach[v]) continue;
    for (uint32_t w : neighbours[v]) {
      if (!unsure[w]) continue;
      const float through = distance + glm::length(surface.positions[w] - surface.positions[v]);
      if (through >= reach[w]) continue;
      reach[w] = through;
      regions[w] = regions[v];
      front.push({through, w});
    }
  }
  for (size_t v = 0; v < n; ++v) regions[v] = regions[surface.rootOf(v)];
  return regions;
}

FaceSurface gatherSurface(const eng::Model& model, const PosedFace& posed, const FaceParts& parts,
                          std::initializer_list<FacePart> wanted) {
  FaceSurface surface;
  std::vector<uint32_t> index;
  for (size_t pi = 0; pi < posed.primitives.size() && pi < parts.vertexParts.size(); ++pi) {
    const PosedPrimitive& p = posed.primitives[pi];
    const eng::Primitive& primitive = model.meshes[p.mesh].primitives[p.primitive];
    const std::vector<FacePart>& vertexParts = parts.vertexParts[pi];
    if (vertexParts.size() != p.positions.size()) continue;
    index.assign(p.positions.size(), kNotGathered);
    for (size_t v = 0; v < p.positions.size(); ++v) {
      if (std::find(wanted.begin(), wanted.end(), vertexParts[v]) == wanted.end()) continue;
      index[v] = uint32_t(surface.positions.size());
      surface.vertices.push_back({uint32_t(pi), uint32_t(v)});
      surface.parts.push_back(vertexParts[v]);
      surface.positions.push_back(p.positions[v]);
      surface.seamRoot.push_back(index[v]);
    }
    for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
      std::array<uint32_t, 3> t{};
      bool whole = true;
      for (int k = 0; k < 3; ++k) {
        uint32_t v = primitive.indices[i + size_t(k)];
        whole = whole && v < index.size() && index[v] != kNotGathered;
        if (whole) t[size_t(k)] = index[v];
      }
      if (whole) surface.triangles.push_back(t);
    }
    if (primitive.texcoords.size() != primitive.vertexCount()) continue;
    // A seam copy's root: the first gathered vertex at its place.
    const eng::ExactPositionGroups groups = eng::groupExactPositions(p.positions);
    std::vector<uint32_t> first(groups.firstVertex.size(), kNotGathered);
    for (size_t v = 0; v < p.positions.size(); ++v) {
      if (index[v] == kNotGathered) continue;
      uint32_t& root = first[groups.groupOf[v]];
      if (root == kNotGathered) root = uint32_t(v);
      else if (primitive.texcoords[root] != primitive.texcoords[v]) surface.seamRoot[index[v]] = index[root];
    }
  }
  return surface;
}

// A mouth corner's two points' spacing may differ from the source's by this
// much of the mouth's width: the faces' own, as found, differ by up to 0.013
// (facecap), and moving a corner that little off the mesh's own tore 7 of
// facecap's lip edges in anger; noise of 0.02 eye spans moves it by 0.05.
constexpr float kCornerSpacingTolerance = 0.02f;

FaceLandmarks withSteadyMouthCorners(const FaceLandmarks& source, const FaceLandmarks& target) {
  const LandmarkFrame sourceFrame(source), targetFrame(target);
  auto plane = [](const LandmarkFrame& frame, const glm::vec3& v) {
    return glm::vec2(glm::dot(v, frame.side()), glm::dot(v, frame.up()));
  };
  const float sourceWidth = glm::length(plane(sourceFrame, source.points[54] - source.points[48]));
  const float targetWidth = glm::length(plane(targetFrame, target.points[54] - target.points[48]));
  if (!(sourceWidth > 0.0f) || !std::isfinite(targetWidth)) return target;
  FaceLandmarks steady = target;
  for (const auto& [outer, inner] : {std::pair<size_t, size_t>{48, 60}, std::pair<size_t, size_t>{54, 64}}) {
    const glm::vec2 expected = plane(sourceFrame, source.points[inner] - source.points[outer]) * (targetWidth / sourceWidth);
    const glm::vec2 middle = 0.5f * plane(targetFrame, target.points[outer] + target.points[inner]);
    const float tolerance = kCornerSpacingTolerance * targetWidth;
    const glm::vec2 found = plane(targetFrame, target.points[inner] - target.points[outer]);
    const glm::vec2 off = found - expected;
    const glm::vec2 spacing = glm::length(off) > tolerance ? expected + off * (tolerance / glm::length(off)) : found;
    for (const auto& [index, towardsInner] : {std::pair<size_t, float>{outer, -0.5f}, std::pair<size_t, float>{inner, 0.5f}}) {
      const glm::vec2 move = middle + towardsInner * spacing - plane(targetFrame, target.points[index]);
      steady.points[index] += move.x * targetFrame.side() + move.y * targetFrame.up();
    }
  }
  return steady;
}

LandmarkPairs distinctLandmarkPairs(const FaceLandmarks& source, const FaceLandmarks& target) {
  LandmarkPairs pairs;
  pairs.minSeparation = 1e-3f * LandmarkFrame(source).eyeSpan();
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const glm::vec3& s = source.points[i];
    bool met = false;
    for (const glm::vec3& earlier : pairs.source) met = met || glm::length(s - earlier) < 10.0f * pairs.minSeparation;
    if (met) continue;
    pairs.source.push_back(s);
    pairs.target.push_back(target.points[i]);
    pairs.landmark.push_back(uint32_t(i));
  }
  return pairs;
}

eng::Result<Correspondence> correspond(const FaceSurface& source, const FaceLandmarks& sourceLandmarks,
                                       const FaceSurface& target, const FaceLandmarks& targetLandmarks,
                                       const CorrespondenceOptions& options) {
  const LandmarkFrame sourceFrame(sourceLandmarks), targetFrame(targetLandmarks);
  const LandmarkPairs pairs = distinctLandmarkPairs(sourceLandmarks, targetLandmarks);
  const std::vector<glm::vec3>& sourcePoints = pairs.source;
  const std::vector<glm::vec3>& targetPoints = pairs.target;
  const float minSeparation = pairs.minSeparation;
  std::vector<double> smoothing(sourcePoints.size(), 0.0);
  for (size_t i = 0; i < smoothing.size(); ++i)
    if (!passedThrough(pairs.landmark[i])) smoothing[i] = kLandmarkSmoothing;
  LandmarkWarp warp = ENG_TRY_VALUE(LandmarkWarp::build(sourcePoints, targetPoints, minSeparation, smoothing));
  std::vector<glm::vec3> warped = warpAll(warp, source.positions);
  size_t grown = 0;
  for (int round = 0; round < options.growthRounds; ++round) {
    std::vector<glm::vec3> s(sourcePoints), t(targetPoints);
    growPairs(source, warped, target, targetFrame, targetLandmarks, options, s, t);
    // Grown points that crowd a source landmark would make the RBF refuse the set: a round that fails keeps the last warp.
    std::vector<double> withGrown(smoothing);
    withGrown.resize(s.size(), 0.0);  // grown pairs are points of both surfaces: passed through
    eng::Result<LandmarkWarp> next = LandmarkWarp::build(s, t, minSeparation, withGrown);
    if (!next) break;
    warp = std::move(*next);
    grown = s.size() - sourcePoints.size();
    warped = warpAll(warp, source.positions);
  }

  // Regions come from each face's own landmarks: the source's at rest, carried by the warp.
  std::vector<FaceRegion> sourceRegions = labelRegions(source, sourceFrame);
  const TriangleGrid grid(warped, source.triangles, sourceRegions);
  const std::vector<FaceRegion> targetRegions = labelRegions(target, targetFrame);
  const std::vector<glm::vec3> targetNormals = vertexNormals(target.positions, target.triangles);
  Correspondence result{.warp = std::move(warp), .grownPairs = grown, .warpedSource = std::move(warped), .matches = {},
                        .sourceRegions = std::move(sourceRegions), .targetRegions = targetRegions};
  result.matches.resize(target.positions.size());
  const float maxGap = options.maxGap * targetFrame.eyeSpan();
  for (size_t v = 0; v < target.positions.size(); ++v)
    result.matches[v] = grid.closest(target.positions[v], opposite(targetRegions[v]), maxGap, targetNormals[v]);
  return result;
}

}  // namespace autorig
