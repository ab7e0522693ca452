#include "autorig/target_transfer.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string_view>

#include <Eigen/Dense>
#include <glm/gtx/compatibility.hpp>

#include "autorig/arkit_from_geometry.h"
#include "autorig/arkit_from_units.h"
#include "autorig/brow_band.h"
#include "autorig/dense_correspondence.h"
#include "autorig/detail_transfer.h"
#include "autorig/face_frame.h"
#include "autorig/jaw_hinge.h"
#include "engine/scene/normals.h"
#include "facial/runtime/rig/arkit_names.h"

namespace autorig {
namespace {

// Landmarks farther than this from the face's skin (eye spans) are off it;
// more than kMaxOffSurface of them and the landmarks are not this face's.
constexpr float kOffSurface = 0.2f;
constexpr size_t kMaxOffSurface = 10;
// The landmarks' smallest spread (across their best plane) against their
// largest, below which they are flat; a face's is about 0.2.
constexpr double kMinDepth = 0.02;
// A matched target vertex takes the whole displacement up to kFullGap from
// the warped source and none beyond the correspondence's maxGap (eye spans):
// lashes a little off the skin follow, a shoulder does not.
constexpr float kFullGap = 0.05f;
// The lid constraint: within kLidInner eyeball radii of the centre a vertex
// keeps its distance to it; it fades out by kLidOuter.
constexpr float kLidInner = 1.25f, kLidOuter = 1.7f;
// Units that open the jaw: the lower teeth and tongue turn with them.
constexpr std::array<std::string_view, 2> kJawUnits{"AU26_JawDrop", "AU27_MouthStretch"};
// Finite-difference step of the warp's Jacobian, in source eye spans (about
// two millimetres): smooth over the biharmonic kernel's kinks at control
// points, and over the warp's bends between lip landmarks a millimetre off
// (with noise of 0.02 eye spans on the built-in head's landmarks the lips'
// units folded 74 skin triangles a rig at a step of 0.01, 24 at 0.03:
// `TargetTransfer.LandmarksALittleOffFoldLittleSkin`).
constexpr float kJacobianStep = 0.03f;
// The warp's local stretch is kept within this factor of its overall scale:
// where grown pairs crowd, the RBF can fold, and a folded Jacobian would send
// a unit's displacement the wrong way or tenfold.
constexpr float kMaxStretch = 2.0f;
// A vertex a made target moves less than this (eye spans: about a micrometre
// on a person, far under a pixel) is left out of it, and a target that moves
// none is not made. In the face's units a fixed bound made AU19 on facecap
// drawn in centimetres and not in metres.
constexpr float kStillShare = 1e-5f;

bool sameName(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string describeLandmarks(const char* whose) { return std::string(whose) + " landmarks: "; }

eng::Result<void> checkLandmarks(const FaceLandmarks& landmarks, const char* whose) {
  glm::dvec3 mean(0.0);
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const glm::vec3& p = landmarks.points[i];
    if (!std::isfinite(p.x + p.y + p.z))
      return eng::makeError(eng::ErrorKind::InvalidArgument,
                            describeLandmarks(whose) + "point " + std::to_string(i) + " of 68 is not finite");
    mean += glm::dvec3(p);
  }
  mean /= double(kLandmarkCount);
  double spread = 0.0;
  for (const glm::vec3& p : landmarks.points) spread = std::max(spread, glm::length(glm::dvec3(p) - mean));
  const float eyeSpan = glm::length(landmarks.points[45] - landmarks.points[36]);
  if (!(spread > 1e-6) || !(eyeSpan > 1e-3f * float(spread)))
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          describeLandmarks(whose) + "collapsed: the 68 points lie within " + std::to_string(spread) +
                              " of their centre, the eye corners 36 and 45 " + std::to_string(eyeSpan) + " apart");
  // A face has depth (the nose stands out of the eyes' plane): points in one
  // plane are a picture, a sheet or a mistake.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const glm::vec3& p : landmarks.points) {
    const Eigen::Vector3d d(p.x - mean.x, p.y - mean.y, p.z - mean.z);
    covariance += d * d.transpose();
  }
  const Eigen::Vector3d sigma = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues();
  if (!(std::sqrt(std::max(sigma(0), 0.0)) > kMinDepth * std::sqrt(sigma(2))))
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          describeLandmarks(whose) + "flat: the 68 points lie in one plane (depth " +
                              std::to_string(std::sqrt(std::max(sigma(0), 0.0))) + " against a spread of " +
                              std::to_string(std::sqrt(sigma(2))) + "): not a face");
  return {};
}

std::vector<std::string> sourceUnits(const eng::Model& model) {
  std::vector<std::string> units;
  for (const eng::Mesh& mesh : model.meshes)
    for (const std::string& name : mesh.targetNames)
      if (name.size() > 2 && name.starts_with("AU") && std::isdigit(static_cast<unsigned char>(name[2])) &&
          std::find(units.begin(), units.end(), name) == units.end())
        units.push_back(name);
  return units;
}

// Each unit's world displacement of every source vertex.
// Each named target's displacement at each of `vertices` of `model` posed
// as `posed`, in world space (zero where its mesh lacks the target).
std::vector<std::vector<glm::vec3>> worldDeltas(const eng::Model& model, const PosedFace& posed,
                                                std::span<const FaceSurface::VertexRef> vertices,
                                                std::span<const std::string> names) {
  std::vector<std::vector<glm::vec3>> deltas(names.size(), std::vector<glm::vec3>(vertices.size(), glm::vec3(0.0f)));
  // Each mesh's target index for each name (its count where it has none).
  std::vector<std::vector<size_t>> index(model.meshes.size(), std::vector<size_t>(names.size()));
  for (size_t m = 0; m < model.meshes.size(); ++m)
    for (size_t u = 0; u < names.size(); ++u) {
      const std::vector<std::string>& own = model.meshes[m].targetNames;
      index[m][u] = size_t(std::find_if(own.begin(), own.end(), [&](const std::string& n) { return sameName(n, names[u]); }) -
                           own.begin());
    }
  for (size_t i = 0; i < vertices.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[vertices[i].primitive];
    const eng::Primitive& primitive = model.meshes[pp.mesh].primitives[pp.primitive];
    const uint32_t v = vertices[i].vertex;
    const glm::mat3 toWorld = glm::inverse(pp.worldToLocal[v]);
    for (size_t u = 0; u < names.size(); ++u) {
      const size_t t = index[pp.mesh][u];
      if (t >= primitive.targets.size()) continue;
      const std::vector<glm::vec3>& local = primitive.targets[t].positions;
      if (v < local.size()) deltas[u][i] = toWorld * local[v];
    }
  }
  return deltas;
}

std::vector<std::vector<glm::vec3>> sourceDeltas(const SourceFace& source, const FaceSurface& surface,
                                                 const std::vector<std::string>& units) {
  return worldDeltas(*source.model, source.posed, surface.vertices, units);
}

glm::vec3 atMatch(const std::vector<glm::vec3>& perVertex, const FaceSurface& surface, const ClosestPoint& match) {
  const auto& t = surface.triangles[match.triangle];
  return match.barycentric.x * perVertex[t[0]] + match.barycentric.y * perVertex[t[1]] + match.barycentric.z * perVertex[t[2]];
}

// Too many landmarks away from the face's skin: they were found on another
// face, on hair or glasses, or typed wrong.
eng::Result<void> checkOnSurface(const FaceSurface& target, const FaceLandmarks& landmarks, const LandmarkFrame& frame) {
  const TriangleGrid grid(target.positions, target.triangles, {});
  size_t off = 0, worst = 0;
  float worstGap = 0.0f;
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const ClosestPoint hit = grid.closest(landmarks.points[i], FaceRegion::None, kOffSurface * frame.eyeSpan());
    if (hit.found) continue;
    ++off;
    worst = i;
    worstGap = kOffSurface;
  }
  if (off > kMaxOffSurface)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::to_string(off) + " of 68 landmarks are off the face's skin (farther than " +
                              std::to_string(worstGap) + " eye spans; the last is point " + std::to_string(worst) +
                              "): they do not belong to this face");
  return {};
}

// The target seen the other way round from the source (a face from the
// back, or left and right swapped): its forward turns against the source's.
eng::Result<void> checkFacing(const SourceFace& source, const FaceLandmarks& landmarks) {
  const Similarity fit = ENG_TRY_VALUE(fitSimilarity(source.landmarks.points, landmarks.points));
  const glm::vec3 carried = fit.rotation * LandmarkFrame(source.landmarks).forward();
  if (glm::dot(carried, LandmarkFrame(landmarks).forward()) < 0.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "landmarks: the face's 68 points are mirrored (left and right swapped, or seen from the back)");
  return {};
}

// The Jacobian with its singular values clamped to [scale / kMaxStretch,
// scale * kMaxStretch] and a reflection (a fold) undone.
glm::mat3 tamed(const glm::mat3& j, float scale) {
  Eigen::Matrix3f m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m(r, c) = j[c][r];
  Eigen::JacobiSVD<Eigen::Matrix3f> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3f sigma = svd.singularValues().cwiseMax(scale / kMaxStretch).cwiseMin(scale * kMaxStretch);
  Eigen::Matrix3f u = svd.matrixU();
  if (u.determinant() * svd.matrixV().determinant() < 0.0f) u.col(2) = -u.col(2);
  const Eigen::Matrix3f out = u * sigma.asDiagonal() * svd.matrixV().transpose();
  glm::mat3 result;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) result[c][r] = out(r, c);
  return result;
}

struct Moved {
  std::vector<FaceSurface::VertexRef> vertices;  // skin-following vertices, lower teeth and tongue, layers on the skin, still parts
  std::vector<glm::vec3> positions;
  std::vector<NamedDeltas> units;
};

// Vertices no unit moves, after the others: every unit gets zeros for them.
void appendStill(Moved& moved, const FaceSurface& still) {
  moved.vertices.insert(moved.vertices.end(), still.vertices.begin(), still.vertices.end());
  moved.positions.insert(moved.positions.end(), still.positions.begin(), still.positions.end());
  for (NamedDeltas& unit : moved.units) unit.deltas.resize(moved.positions.size(), glm::vec3(0.0f));
}

// A layer on the skin (a beard, a moustache, face paint) moves as the skin under it:
// each of its vertices takes the deltas of the skin below it, found from a
// point the layer's depth behind it along its normal. Carried as skin of its
// own, a beard's vertices over the lips were matched to the head's lips and
// cheeks apart from the skin under them, and a smile broke the moustache
// into pieces; the skin closest to it instead can be the other lip, where
// the lips meet. Farther than a tenth of the eye span from the skin, a
// vertex keeps still.
void appendOnSkin(Moved& moved, const FaceSurface& layer, const FaceSurface& skin, const std::vector<glm::vec3>& skinNormal,
                  float eyeSpan) {
  const size_t first = moved.positions.size();
  appendStill(moved, layer);
  if (layer.positions.empty()) return;
  const TriangleGrid grid(skin.positions, skin.triangles, {});
  const float reach = 0.1f * eyeSpan;
  std::vector<ClosestPoint> closest(layer.positions.size());
  std::vector<float> depths;
  for (size_t v = 0; v < layer.positions.size(); ++v) {
    closest[v] = grid.closest(layer.positions[v], FaceRegion::None, reach);
    if (closest[v].found) depths.push_back(closest[v].distance);
  }
  if (depths.empty()) return;
  std::nth_element(depths.begin(), depths.begin() + ptrdiff_t(depths.size() / 2), depths.end());
  const float depth = depths[depths.size() / 2];
  std::vector<uint32_t> indices;
  for (const auto& t : layer.triangles) indices.insert(indices.end(), t.begin(), t.end());
  const std::vector<glm::vec3> normals = eng::computeSmoothNormals(layer.positions, indices);
  for (size_t v = 0; v < layer.positions.size(); ++v) {
    if (!closest[v].found) continue;
    // Its normal turned away from the skin (a card's winding says nothing).
    glm::vec3 n = normals[v];
    if (glm::dot(n, atMatch(skinNormal, skin, closest[v])) < 0.0f) n = -n;
    ClosestPoint under = closest[v];
    if (std::isfinite(glm::dot(n, n)))
      if (const ClosestPoint below = grid.closest(layer.positions[v] - n * depth, FaceRegion::None, reach); below.found) under = below;
    for (NamedDeltas& unit : moved.units) unit.deltas[first + v] = atMatch(unit.deltas, skin, under);
  }
}

// The skin's smooth normals, per vertex of `skin` (outward for glTF's
// counter-clockwise front faces).
std::vector<glm::vec3> skinNormals(const FaceSurface& skin) {
  std::vector<uint32_t> indices;
  indices.reserve(skin.triangles.size() * 3);
  for (const auto& t : skin.triangles) indices.insert(indices.end(), t.begin(), t.end());
  return eng::computeSmoothNormals(skin.positions, indices);
}

// Lids slide over the eyeball: a vertex near an eye keeps its distance to
// the eye's centre, so a blink closes along the ball instead of through it.
glm::vec3 alongEyeball(const glm::vec3& p, const glm::vec3& delta, const FaceParts& parts) {
  glm::vec3 result = delta;
  for (size_t e = 0; e < 2; ++e) {
    const float r = parts.eyeRadii[e];
    if (!(r > 0.0f)) continue;
    const glm::vec3 c = parts.eyeCentres[e];
    const float d = glm::length(p - c);
    if (d >= kLidOuter * r || d < 1e-6f) continue;
    const glm::vec3 moved = p + delta - c;
    const float length = glm::length(moved);
    if (length < 1e-6f) continue;
    const glm::vec3 onSphere = c + moved * (d / length) - p;
    result = glm::mix(delta, onSphere, 1.0f - glm::smoothstep(kLidInner * r, kLidOuter * r, d));
  }
  return result;
}

}  // namespace

namespace {

// The lid landmarks of each eye (right, left): upper pair, lower pair.
constexpr std::array<std::array<size_t, 4>, 2> kLidLandmarks{{{37, 38, 41, 40}, {43, 44, 47, 46}}};
// A unit closes an eye when it turns the upper lid this share of the way to the lower.
constexpr float kClosing = 0.2f;
// Around an eye (eyeball radii from its centre) a closing unit is all turn; beyond, the carried displacement.
constexpr float kLidTurnInner = 1.25f, kLidTurnOuter = 1.75f;

struct EyeLids {
  JawHinge axis;  // through the eye's centre, towards the subject's left
  glm::vec3 upper{0.0f}, lower{0.0f};  // the lids' margins (landmark pair middles)
  glm::vec3 cornerRight{0.0f}, cornerLeft{0.0f};  // the eye's corners (36, 39 or 42, 45)
  glm::vec3 forward{0.0f, 0.0f, 1.0f};             // out of the face
  float radius = 0.0f;
  float openAngle() const { return std::abs(hingeAngle(axis, upper, lower - upper)); }
};

// The lids' margins: where the skin has an opening over the eye, its rim's
// middle above and below the ball (the landmarks sit on the visible edge,
// a little inside the margins); else the lid landmarks.
EyeLids eyeLids(const FaceLandmarks& landmarks, const FaceParts& parts, size_t eye, const FaceSurface& surface,
                const std::vector<FaceRegion>& regions, const std::vector<char>& onRim) {
  const auto& l = kLidLandmarks[eye];
  const LandmarkFrame frame(landmarks);
  EyeLids lids{.axis = {.pivot = parts.eyeCentres[eye], .axis = frame.side()},
               .upper = (landmarks.points[l[0]] + landmarks.points[l[1]]) * 0.5f,
               .lower = (landmarks.points[l[2]] + landmarks.points[l[3]]) * 0.5f,
               .cornerRight = landmarks.points[eye == 0 ? 36 : 42],
               .cornerLeft = landmarks.points[eye == 0 ? 39 : 45],
               .forward = frame.forward(),
               .radius = parts.eyeRadii[eye]};
  const FaceRegion upper = eye == 0 ? FaceRegion::RightUpperLid : FaceRegion::LeftUpperLid;
  const FaceRegion lower = opposite(upper);
  const float middle = frame.sideOf(lids.axis.pivot);
  float bestUpper = std::numeric_limits<float>::max(), bestLower = bestUpper;
  glm::vec3 rimUpper(0.0f), rimLower(0.0f);
  for (size_t v = 0; v < surface.positions.size(); ++v) {
    if (!onRim[v]) continue;
    const glm::vec3& p = surface.positions[v];
    if (glm::length(p - lids.axis.pivot) > 1.6f * lids.radius || glm::dot(p - lids.axis.pivot, frame.forward()) < 0.0f) continue;
    const float off = std::abs(frame.sideOf(p) - middle);
    if (regions[v] == upper && off < bestUpper) bestUpper = off, rimUpper = p;
    if (regions[v] == lower && off < bestLower) bestLower = off, rimLower = p;
  }
  if (bestUpper < 0.1f && bestLower < 0.1f) lids.upper = rimUpper, lids.lower = rimLower;
  return lids;
}

// Columns across an eye for the closing turn's gain, and how far beyond the
// corners (in eye widths) the gain fades back to 1.
constexpr size_t kLidColumns = 8;
constexpr float kColumnFade = 0.2f;
constexpr float kMaxColumnGain = 2.0f;

// Where p lies across the eye: 0 at its corner on the subject's right, 1 at the other.
float columnOf(const EyeLids& eye, const glm::vec3& p) {
  const float width = glm::dot(eye.cornerLeft - eye.cornerRight, eye.axis.axis);
  return width > 0.0f ? glm::dot(p - eye.cornerRight, eye.axis.axis) / width : 0.5f;
}

struct LidColumns {
  LidColumns() { gain.fill(1.0f); }
  std::array<float, kLidColumns> gain;
  // Between the columns' middles linearly; past the corners fading to 1.
  float at(float t) const {
    const float x = std::clamp(t, 0.0f, 1.0f) * float(kLidColumns) - 0.5f;
    const size_t i = size_t(std::clamp(x, 0.0f, float(kLidColumns - 1)));
    const size_t j = std::min(i + 1, kLidColumns - 1);
    const float inside = glm::mix(gain[i], gain[j], std::clamp(x - float(i), 0.0f, 1.0f));
    const float beyond = std::max(-t, t - 1.0f);
    return glm::mix(inside, 1.0f, glm::smoothstep(0.0f, kColumnFade, beyond));
  }
};

// The turn that closes the lid's middle by the source's share can leave a
// column of the target's eye open: the share each vertex follows is carried
// from the source, whose opening narrows towards its corners otherwise
// (Ready Player Me's inner corners kept a sliver of white at a blink). In
// each column across the eye the upper lid's margin (the upper-lid vertex on
// the ball's front nearest the lower lid) is measured against the lower
// lid's, and that column's turn scaled up so the margin closes the same share
// of its own column's opening as the middle does (never down: a column the
// turn closes already stays as it was). Where the skin has an opening over
// the eye, each margin is its rim, read at each column's middle between the
// rim's vertices: a coarse lid (facecap's, a vertex or two per column) had
// columns whose nearest lower-lid vertex lay below the rim, and their doubled
// turn closed the eye in a V.
LidColumns closingColumns(const EyeLids& to, float targetAngle, float share, const FaceSurface& tgt,
                          const std::vector<FaceRegion>& regions, FaceRegion upper,
                          const std::vector<float>& follow, const std::vector<char>& onRim) {
  LidColumns columns;
  const float closing = targetAngle < 0.0f ? -1.0f : 1.0f;
  std::array<float, kLidColumns> upperAt, lowerAt, upperFollow{};
  upperAt.fill(-std::numeric_limits<float>::infinity());
  lowerAt.fill(std::numeric_limits<float>::infinity());
  struct RimPoint {
    float t, along, follow;
  };
  std::vector<RimPoint> upperRim, lowerRim;
  for (size_t v = 0; v < tgt.positions.size(); ++v) {
    const glm::vec3& p = tgt.positions[v];
    const glm::vec3 out = p - to.axis.pivot;
    const float distance = glm::length(out);
    // On the ball's front: the lids' margins, not the socket behind the ball.
    if (distance < 0.9f * to.radius || distance > kLidTurnInner * to.radius ||
        glm::dot(out, to.forward) < 0.3f * to.radius)
      continue;
    const float t = columnOf(to, p);
    if (!(t >= -0.25f && t < 1.25f)) continue;
    const float along = closing * hingeAngle(to.axis, to.lower, p - to.lower);  // < 0: above the lower lid's middle
    if (onRim[v] && regions[v] == upper) upperRim.push_back({t, along, follow[v]});
    if (onRim[v] && regions[v] == opposite(upper)) lowerRim.push_back({t, along, follow[v]});
    if (!(t >= 0.0f && t < 1.0f)) continue;
    const size_t k = size_t(t * float(kLidColumns));
    if (regions[v] == upper && along > upperAt[k]) upperAt[k] = along, upperFollow[k] = follow[v];
    if (regions[v] == opposite(upper) && along < lowerAt[k]) lowerAt[k] = along;
  }
  // The rim as a line across the eye: at t, between the rim vertices on either side.
  auto acrossRim = [](const std::vector<RimPoint>& rim, float t) {
    const auto after = std::lower_bound(rim.begin(), rim.end(), t, [](const RimPoint& r, float x) { return r.t < x; });
    if (after == rim.begin()) return *after;
    if (after == rim.end()) return rim.back();
    const RimPoint& before = *(after - 1);
    const float w = after->t > before.t ? (t - before.t) / (after->t - before.t) : 0.0f;
    return RimPoint{t, glm::mix(before.along, after->along, w), glm::mix(before.follow, after->follow, w)};
  };
  auto spans = [](const std::vector<RimPoint>& rim) { return rim.size() >= 3 && rim.front().t < 0.2f && rim.back().t > 0.8f; };
  auto byT = [](const RimPoint& a, const RimPoint& b) { return a.t < b.t; };
  std::sort(upperRim.begin(), upperRim.end(), byT);
  std::sort(lowerRim.begin(), lowerRim.end(), byT);
  if (spans(upperRim) && spans(lowerRim))
    for (size_t k = 0; k < kLidColumns; ++k) {
      const float middle = (float(k) + 0.5f) / float(kLidColumns);
      const RimPoint up = acrossRim(upperRim, middle);
      upperAt[k] = up.along, upperFollow[k] = up.follow;
      lowerAt[k] = acrossRim(lowerRim, middle).along;
    }
  std::array<bool, kLidColumns> measured{};
  for (size_t k = 0; k < kLidColumns; ++k) {
    const float got = upperFollow[k] * std::abs(targetAngle);
    if (!std::isfinite(upperAt[k]) || !std::isfinite(lowerAt[k]) || !(got > 1e-4f)) continue;
    const float needed = share * (lowerAt[k] - upperAt[k]);
    columns.gain[k] = std::clamp(needed / got, 1.0f, kMaxColumnGain);
    measured[k] = true;
  }
  // A column without a vertex on each margin (a coarse lid) takes its measured neighbours' mean.
  const std::array<float, kLidColumns> gains = columns.gain;
  for (size_t k = 0; k < kLidColumns; ++k) {
    if (measured[k]) continue;
    float sum = 0.0f;
    int n = 0;
    for (size_t i = k; i-- > 0;)
      if (measured[i]) { sum += gains[i], ++n; break; }
    for (size_t i = k + 1; i < kLidColumns; ++i)
      if (measured[i]) { sum += gains[i], ++n; break; }
    if (n > 0) columns.gain[k] = sum / float(n);
  }
  return columns;
}

// A closing unit as the upper lid turning over the eyeball about its centre
// (so the lid slides along the ball and meets the lower lid): how far each
// source vertex follows its own lid's turn is carried over as a number, and
// the target's lid turns as large a share of its own opening as the
// source's does.
using BothEyes = std::array<EyeLids, 2>;  // right, left

void closeLids(const BothEyes& sourceEyes, const BothEyes& targetEyes, const TriangleGrid& sourceGrid,
               const FaceSurface& src, const std::vector<glm::vec3>& raw, const FaceSurface& tgt,
               const std::vector<char>& onRim, const Correspondence& corr, std::vector<glm::vec3>& deltas) {
  for (size_t eye = 0; eye < 2; ++eye) {
    const EyeLids& from = sourceEyes[eye];
    const EyeLids& to = targetEyes[eye];
    if (!(from.radius > 0.0f) || !(to.radius > 0.0f) || !(from.openAngle() > 0.0f)) continue;
    const ClosestPoint margin = sourceGrid.closest(from.upper, FaceRegion::None, 1e9f);
    if (!margin.found) continue;
    const float angle = hingeAngle(from.axis, from.upper, atMatch(raw, src, margin));
    const float share = std::abs(angle) / from.openAngle();
    if (share < kClosing) continue;
    std::vector<glm::vec3> follow(src.positions.size(), glm::vec3(0.0f));
    for (size_t i = 0; i < src.positions.size(); ++i) {
      const glm::vec3 full = turnAboutHinge(from.axis, angle, src.positions[i]);
      const float energy = glm::dot(full, full);
      if (energy > 0.0f) follow[i].x = std::clamp(glm::dot(raw[i], full) / energy, 0.0f, 1.0f);
    }
    const float targetAngle = std::copysign(share * to.openAngle(), angle);
    std::vector<float> targetFollow(tgt.positions.size(), 0.0f);
    for (size_t v = 0; v < tgt.positions.size(); ++v)
      if (corr.matches[v].found) targetFollow[v] = atMatch(follow, src, corr.matches[v]).x;
    // Only a unit that closes the eye (its turn takes the upper lid towards the lower) is closed column by column.
    const bool closes = angle * hingeAngle(from.axis, from.upper, from.lower - from.upper) > 0.0f;
    const FaceRegion upper = eye == 0 ? FaceRegion::RightUpperLid : FaceRegion::LeftUpperLid;
    LidColumns columns;
    if (closes) columns = closingColumns(to, targetAngle, share, tgt, corr.targetRegions, upper, targetFollow, onRim);
    for (size_t v = 0; v < tgt.positions.size(); ++v) {
      const float near = 1.0f - glm::smoothstep(kLidTurnInner * to.radius, kLidTurnOuter * to.radius,
                                                glm::length(tgt.positions[v] - to.axis.pivot));
      if (near <= 0.0f || !corr.matches[v].found) continue;
      const float turn = targetAngle * columns.at(columnOf(to, tgt.positions[v]));
      deltas[v] = glm::mix(deltas[v], targetFollow[v] * turnAboutHinge(to.axis, turn, tgt.positions[v]), near);
    }
  }
}

struct JawTurn {
  JawHinge source, target;
  float angle = 0.0f;  // the source's chin about its hinge
};

// A jaw unit split on the source: how far each vertex follows its jaw's
// turn (its displacement along the turn's, 0 above the lips, 1 on the chin)
// and what is left (lips parting further than the jaw turns them).
struct JawSplit {
  std::vector<glm::vec3> follow;    // the share in x (a number carried as a vector)
  std::vector<glm::vec3> residual;  // carried like any unit
};

JawSplit splitJaw(const JawTurn& turn, const FaceSurface& src, const std::vector<glm::vec3>& raw) {
  JawSplit split{std::vector<glm::vec3>(src.positions.size(), glm::vec3(0.0f)), raw};
  for (size_t i = 0; i < src.positions.size(); ++i) {
    const glm::vec3 full = turnAboutHinge(turn.source, turn.angle, src.positions[i]);
    const float energy = glm::dot(full, full);
    if (!(energy > 0.0f)) continue;
    split.follow[i].x = std::clamp(glm::dot(raw[i], full) / energy, 0.0f, 1.0f);
    split.residual[i] -= split.follow[i].x * full;
  }
  return split;
}

// The turn of a jaw unit about the target's hinge, added to its carried
// residual: so the lips part along the mouth line and the chin swings
// instead of stretching. What the source has nothing close to below the lips
// (the inside of a deeper mouth), the lower teeth and the tongue turn fully.
void turnWithJaw(const JawTurn& turn, const JawSplit& split, const FaceSurface& src, const FaceSurface& tgt,
                 const Correspondence& corr, float fullGap, float maxGap, const FaceSurface& jaw,
                 std::vector<glm::vec3>& deltas) {
  for (size_t v = 0; v < tgt.positions.size(); ++v) {
    const ClosestPoint& match = corr.matches[v];
    const float matched = match.found ? 1.0f - glm::smoothstep(fullGap, maxGap, match.distance) : 0.0f;
    float share = match.found ? matched * atMatch(split.follow, src, match).x : 0.0f;
    if (corr.targetRegions[v] == FaceRegion::LowerLip) share += 1.0f - matched;
    deltas[v] += share * turnAboutHinge(turn.target, turn.angle, tgt.positions[v]);
  }
  for (size_t j = 0; j < jaw.positions.size(); ++j)
    deltas[tgt.positions.size() + j] = turnAboutHinge(turn.target, turn.angle, jaw.positions[j]);
}

// How far a unit's displacements raise a lip's inner middle (landmarks
// `first` to first + 2, at the nearest vertex on that lip), along the face's up.
float lipRise(const FaceSurface& surface, const std::vector<FaceRegion>& regions, const FaceLandmarks& landmarks,
              const std::vector<glm::vec3>& deltas, size_t first, FaceRegion lip) {
  const glm::vec3 up = LandmarkFrame(landmarks).up();
  float sum = 0.0f;
  for (size_t i = first; i < first + 3; ++i) {
    size_t best = surface.positions.size();
    float bestDistance = std::numeric_limits<float>::max();
    for (size_t v = 0; v < surface.positions.size(); ++v) {
      const float d = glm::length(surface.positions[v] - landmarks.points[i]);
      if (regions[v] == lip && d < bestDistance) bestDistance = d, best = v;
    }
    if (best < surface.positions.size()) sum += glm::dot(deltas[best], up);
  }
  return sum / 3.0f;
}

// The frontmost lower-teeth vertex of a jaw surface, or its size when it has none.
size_t frontTooth(const FaceSurface& jaw, const LandmarkFrame& frame) {
  size_t front = jaw.positions.size();
  float frontmost = -std::numeric_limits<float>::max();
  for (size_t j = 0; j < jaw.positions.size(); ++j)
    if (jaw.parts[j] == FacePart::LowerTeeth && glm::dot(jaw.positions[j], frame.forward()) > frontmost)
      frontmost = glm::dot(jaw.positions[j], frame.forward()), front = j;
  return front;
}

// How far the source's lower teeth drop under each unit for the lower lip's
// middle (0 where it has no teeth or the unit opens nothing).
std::vector<float> sourceTeethShares(const SourceFace& source, const FaceSurface& src, const std::vector<FaceRegion>& regions,
                                     const std::vector<std::vector<glm::vec3>>& raw, const std::vector<std::string>& units) {
  std::vector<float> shares(units.size(), 0.0f);
  const FaceSurface jaw = gatherSurface(*source.model, source.posed, source.parts, {FacePart::LowerTeeth});
  const LandmarkFrame frame(source.landmarks);
  const size_t front = frontTooth(jaw, frame);
  if (front == jaw.positions.size()) return shares;
  const std::vector<std::vector<glm::vec3>> teeth = sourceDeltas(source, jaw, units);
  for (size_t u = 0; u < units.size(); ++u) {
    const float lip = lipRise(src, regions, source.landmarks, raw[u], 65, FaceRegion::LowerLip);
    const float tooth = glm::dot(teeth[u][front], frame.up());
    if (lip < 0.0f && tooth < 0.0f) shares[u] = tooth / lip;
  }
  return shares;
}

// A face's lower teeth (and its tongue), carried from the source or its own,
// drop at least as far, for the lower lip's middle, as they do in the source:
// the turn found for the lips (scaled down where they part more than the jaw
// turns them) left them floating in a scan's open mouth at 0.6 of the head's
// travel, and bared facecap's own to the roots when surprise opened its
// mouth (its own jawOpen drops them 0.9 of its lip's way). The turn is only
// raised, up to kTeethScale.
constexpr float kTeethScale = 2.0f;

void lowerTeethWithTheLip(const JawTurn& turn, float share, const FaceSurface& tgt, const Correspondence& corr,
                          const FaceLandmarks& landmarks, const FaceSurface& jaw, std::vector<glm::vec3>& deltas) {
  const LandmarkFrame frame(landmarks);
  const size_t front = frontTooth(jaw, frame);
  if (front == jaw.positions.size() || !(share > 0.0f)) return;
  const float lip = lipRise(tgt, corr.targetRegions, landmarks, deltas, 65, FaceRegion::LowerLip);
  const float teeth = glm::dot(deltas[tgt.positions.size() + front], frame.up());
  if (!(lip < 0.0f && teeth < 0.0f)) return;
  const float angle = turn.angle * std::clamp(share * lip / teeth, 1.0f, kTeethScale);
  for (size_t j = 0; j < jaw.positions.size(); ++j)
    deltas[tgt.positions.size() + j] = turnAboutHinge(turn.target, angle, jaw.positions[j]);
}

// The jaw's turn that opens the target's mouth as wide, for its width, as
// the source's turn opens the source's: the angle carried from the source's
// chin opens a longer face's mouth less (the lips lie nearer the hinge than
// the chin does), and the hinges are estimated from each face's own jaw line.
// Measured where the turn takes the lower lip's inner middle (65-67) down,
// over the mouth's width (48-54): landmarks only, so a few landmarks a
// millimetre off change it by a few hundredths. Measured on the made skin
// instead (the lips' gap at the vertices nearest those points, the carried
// residual and the mended tears counted in), noise of 0.02 eye spans on the
// landmarks put facecap's scale anywhere from 1.36 to 1.99 and the built-in
// head's (rigged from itself) from 0.48 to 1.37 (now 1.05-1.20, 0.73-0.86),
// and facecap's made jawOpen moved 1.24 times its own (now 1.07).
// Scaled within [1/kJawScale, kJawScale].
constexpr float kJawScale = 2.5f;

// A jaw unit opens the lips as one sheet of skin. Each skin vertex about the
// mouth takes the lip it is labelled with, and where the lips' skin folds at
// the meeting line's height (the lining inside the corners, a lip's rim) or
// where a seam's copies were labelled apart, neighbours take different lips:
// carried as they are, the jaw opens triangles there into slivers a lip's
// height long and notches the rim. A few relaxation passes about each tear
// (an edge the unit stretches past kTear times its length) grade the step
// over a few edges, as skin stretches; the rest is held. Every unit: the
// lips' own (the upper lip raiser, the lower lip depressor) open them by
// millimetres, but the lining inside Ready Player Me's mouth corners is
// finer still, and anger and disgust hung it over the teeth as dark spikes.
constexpr int kTearPasses = 8;
constexpr float kTear = 3.0f;

struct LipSheet {
  std::vector<uint32_t> vertices;                 // skin about the mouth, a UV seam's copies by their first
  std::vector<int32_t> slot;                      // per target vertex, its index in `vertices` (-1: none)
  std::vector<std::vector<uint32_t>> neighbours;  // per listed vertex, the vertices across its edges (seam copies by their first)
};

LipSheet lipSheetOf(const FaceSurface& tgt, const std::vector<FaceRegion>& regions) {
  LipSheet sheet;
  std::vector<int32_t>& slot = sheet.slot;
  slot.assign(tgt.positions.size(), -1);
  for (uint32_t v = 0; v < tgt.positions.size(); ++v) {
    const bool lip = regions[v] == FaceRegion::UpperLip || regions[v] == FaceRegion::LowerLip;
    if (tgt.rootOf(v) != v || !lip || tgt.parts[v] != FacePart::Skin) continue;
    slot[v] = int32_t(sheet.vertices.size());
    sheet.vertices.push_back(v);
  }
  sheet.neighbours.resize(sheet.vertices.size());
  for (const auto& t : tgt.triangles)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = tgt.rootOf(t[k]), b = tgt.rootOf(t[(k + 1) % 3]);
      if (slot[a] >= 0) sheet.neighbours[size_t(slot[a])].push_back(b);
      if (slot[b] >= 0) sheet.neighbours[size_t(slot[b])].push_back(a);
    }
  for (std::vector<uint32_t>& n : sheet.neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return sheet;
}

void mendTears(const LipSheet& sheet, const FaceSurface& tgt, std::vector<glm::vec3>& deltas) {
  const std::vector<int32_t>& slot = sheet.slot;
  // The torn vertices and their neighbours relax; every other vertex holds.
  std::vector<bool> relaxed(sheet.vertices.size(), false);
  for (size_t i = 0; i < sheet.vertices.size(); ++i) {
    const uint32_t v = sheet.vertices[i];
    const bool torn = std::any_of(sheet.neighbours[i].begin(), sheet.neighbours[i].end(), [&](uint32_t n) {
      return glm::length(deltas[v] - deltas[n]) > kTear * glm::length(tgt.positions[v] - tgt.positions[n]);
    });
    if (!torn) continue;
    relaxed[i] = true;
    for (uint32_t n : sheet.neighbours[i])
      if (slot[n] >= 0) relaxed[size_t(slot[n])] = true;
  }
  std::vector<glm::vec3> next(sheet.vertices.size());
  for (int pass = 0; pass < kTearPasses; ++pass) {
    for (size_t i = 0; i < sheet.vertices.size(); ++i) {
      next[i] = deltas[sheet.vertices[i]];
      if (!relaxed[i] || sheet.neighbours[i].empty()) continue;
      glm::vec3 mean(0.0f);
      for (uint32_t n : sheet.neighbours[i]) mean += deltas[n];
      next[i] = 0.5f * next[i] + 0.5f * mean / float(sheet.neighbours[i].size());
    }
    for (size_t i = 0; i < sheet.vertices.size(); ++i) deltas[sheet.vertices[i]] = next[i];
  }
  for (size_t v = 0; v < tgt.positions.size(); ++v) deltas[v] = deltas[tgt.rootOf(v)];
}

JawTurn openingLikeSource(JawTurn turn, const FaceLandmarks& sourceLandmarks, const FaceLandmarks& landmarks) {
  auto lipDrop = [&](const JawHinge& hinge, const FaceLandmarks& l) {
    const glm::vec3 lowerLip = (l.points[65] + l.points[66] + l.points[67]) / 3.0f;
    const float width = glm::length(l.points[54] - l.points[48]);
    return -glm::dot(turnAboutHinge(hinge, turn.angle, lowerLip), LandmarkFrame(l).up()) / width;
  };
  const float wanted = lipDrop(turn.source, sourceLandmarks), made = lipDrop(turn.target, landmarks);
  if (std::abs(made) > 1e-6f && wanted / made > 0.0f) turn.angle *= std::clamp(wanted / made, 1.0f / kJawScale, kJawScale);
  return turn;
}

// "brows found (the subject's right, left): 52 vertices, down to 0.11 and
// 0.14 eye spans under the brow line, rise with them as one piece".
std::string browsNote(const BrowBand& brows) {
  auto reach = [](float r) {
    char text[16];
    std::snprintf(text, sizeof text, "%.2f", double(r));
    return r > 0.0f ? std::string(text) : std::string("none");
  };
  return "brows found (the subject's right, left): " +
         std::to_string(brows.brows[0].covered.size() + brows.brows[1].covered.size()) + " vertices, down to " +
         reach(brows.brows[0].reach) + " and " + reach(brows.brows[1].reach) +
         " eye spans under the brow line, rise with them as one piece";
}

// The units whose brows move as one piece (autorig/brow_band.h).
bool raisesBrows(std::string_view unit) {
  return unit == "AU1_InnerBrowRaiser" || unit.starts_with("AU2_OuterBrowRaiser");
}

Moved carryUnits(const SourceFace& source, const FaceSurface& src, const FaceSurface& tgt, const FaceSurface& jaw,
                 const Correspondence& corr, const std::vector<std::string>& units, const FaceLandmarks& landmarks,
                 const FaceParts& parts, const BrowBand& brows) {
  const LandmarkFrame sourceFrame(source.landmarks), targetFrame(landmarks);
  const std::vector<std::vector<glm::vec3>> raw = sourceDeltas(source, src, units);
  const std::vector<float> teethShare = sourceTeethShares(source, src, corr.sourceRegions, raw, units);
  std::vector<glm::mat3> jacobians(src.positions.size());
  for (size_t i = 0; i < src.positions.size(); ++i)
    jacobians[i] = tamed(corr.warp.jacobian(src.positions[i], kJacobianStep * sourceFrame.eyeSpan()), corr.warp.similarity().scale);

  Moved moved;
  moved.vertices = tgt.vertices;
  moved.positions = tgt.positions;
  moved.vertices.insert(moved.vertices.end(), jaw.vertices.begin(), jaw.vertices.end());
  moved.positions.insert(moved.positions.end(), jaw.positions.begin(), jaw.positions.end());
  const float maxGap = CorrespondenceOptions{}.maxGap * targetFrame.eyeSpan();
  const float fullGap = kFullGap * targetFrame.eyeSpan();

  // The source's chin and its jaw hinge give each jaw unit's angle.
  const TriangleGrid sourceGrid(src.positions, src.triangles, {});
  const ClosestPoint chin = sourceGrid.closest(source.landmarks.points[8], FaceRegion::None, maxGap);
  const JawHinge sourceHinge = estimateJawHinge(source.landmarks), targetHinge = estimateJawHinge(landmarks);

  const std::vector<char> sourceRims = openingRims(src), targetRims = openingRims(tgt);
  const BothEyes sourceEyes{eyeLids(source.landmarks, source.parts, 0, src, corr.sourceRegions, sourceRims),
                            eyeLids(source.landmarks, source.parts, 1, src, corr.sourceRegions, sourceRims)};
  const BothEyes targetEyes{eyeLids(landmarks, parts, 0, tgt, corr.targetRegions, targetRims),
                            eyeLids(landmarks, parts, 1, tgt, corr.targetRegions, targetRims)};
  const LipSheet lips = lipSheetOf(tgt, corr.targetRegions);
  std::vector<glm::vec3> carried(src.positions.size());
  for (size_t u = 0; u < units.size(); ++u) {
    const bool jawUnit = std::find(kJawUnits.begin(), kJawUnits.end(), units[u]) != kJawUnits.end() && chin.found;
    const JawTurn turn{sourceHinge, targetHinge, jawUnit ? hingeAngle(sourceHinge, chin.position, atMatch(raw[u], src, chin)) : 0.0f};
    const JawSplit split = jawUnit ? splitJaw(turn, src, raw[u]) : JawSplit{};
    const std::vector<glm::vec3>& moving = jawUnit ? split.residual : raw[u];
    for (size_t i = 0; i < carried.size(); ++i) carried[i] = jacobians[i] * moving[i];
    NamedDeltas unit{units[u], std::vector<glm::vec3>(moved.positions.size(), glm::vec3(0.0f))};
    for (size_t v = 0; v < tgt.positions.size(); ++v) {
      const ClosestPoint& match = corr.matches[v];
      if (!match.found) continue;
      const float weight = 1.0f - glm::smoothstep(fullGap, maxGap, match.distance);
      unit.deltas[v] = weight * atMatch(carried, src, match);
    }
    if (raisesBrows(units[u])) moveAsOnePiece(brows, targetFrame.up(), unit.deltas);
    closeLids(sourceEyes, targetEyes, sourceGrid, src, raw[u], tgt, targetRims, corr, unit.deltas);
    for (size_t v = 0; v < tgt.positions.size(); ++v) unit.deltas[v] = alongEyeball(tgt.positions[v], unit.deltas[v], parts);
    if (jawUnit) {
      const JawTurn matched = openingLikeSource(turn, source.landmarks, landmarks);
      turnWithJaw(matched, split, src, tgt, corr, fullGap, maxGap, jaw, unit.deltas);
      lowerTeethWithTheLip(matched, teethShare[u], tgt, corr, landmarks, jaw, unit.deltas);
    }
    mendTears(lips, tgt, unit.deltas);
    moved.units.push_back(std::move(unit));
  }
  return moved;
}

// A unit the face has its own shape for (Ready Player Me's default
// `mouthSmile`, `mouthOpen` and `eyesClosed`) is made from that shape instead
// of carried from the head: the author's smile and blink, their sides apart,
// and the author's open mouth, teeth and all.
struct OwnShape {
  std::string_view name;         // the face's target
  std::string_view left, right;  // the units made from its two halves; right empty: left is made from the whole
};
constexpr std::array kOwnShapes = {OwnShape{"mouthSmile", "AU12_LipCornerPuller_L", "AU12_LipCornerPuller_R"},
                                   OwnShape{"mouthOpen", "AU26_JawDrop", ""},
                                   OwnShape{"eyesClosed", "AU45_Blink_L", "AU45_Blink_R"}};
// Eye spans either side of the midline over which the halves blend.
constexpr float kMidlineBlend = 0.1f;

// The face's own spelling of ARKit shape `canonical` ("mouthSmile_L" for
// mouthSmileLeft), empty when it has none.
std::string ownArkitName(const eng::Model& face, std::string_view canonical) {
  const std::optional<uint32_t> index = facial::arkitIndex(canonical);
  for (const eng::Mesh& mesh : face.meshes)
    for (const std::string& name : mesh.targetNames)
      if (facial::arkitIndex(name) == index) return name;
  return {};
}

// A unit whose every ARKit shape the face has (a few of ARKit's 52: a blink,
// a smile, an open jaw) is made from them, as arkitFromUnits would split it:
// the author's shapes, not the head's carried.
void useOwnArkitShapes(const eng::Model& face, const PosedFace& posed, Moved& moved, std::vector<std::string>& taken,
                       std::vector<std::string>& notes) {
  for (NamedDeltas& unit : moved.units) {
    if (std::find(taken.begin(), taken.end(), unit.name) != taken.end()) continue;
    const std::vector<ShapeShare> shares = shapesOfUnit(unit.name);
    if (shares.empty()) continue;
    std::vector<std::string> names;
    for (const ShapeShare& share : shares)
      if (std::string name = ownArkitName(face, share.shape); !name.empty()) names.push_back(std::move(name));
    if (names.size() != shares.size()) continue;
    const std::vector<std::vector<glm::vec3>> deltas = worldDeltas(face, posed, moved.vertices, names);
    std::vector<glm::vec3> sum(moved.vertices.size(), glm::vec3(0.0f));
    for (size_t s = 0; s < shares.size(); ++s)
      for (size_t k = 0; k < sum.size(); ++k) sum[k] += shares[s].gain * deltas[s][k];
    if (std::all_of(sum.begin(), sum.end(), [](const glm::vec3& d) { return d == glm::vec3(0.0f); })) continue;
    unit.deltas = std::move(sum);
    std::string line = unit.name + ": the face's own ";
    for (size_t s = 0; s < names.size(); ++s) {
      if (s > 0) line += " + ";
      if (shares[s].gain != 1.0f) {
        char gain[32];
        std::snprintf(gain, sizeof gain, "%.2g x ", double(shares[s].gain));
        line += gain;
      }
      line += names[s];
    }
    notes.push_back(line + " (not carried from the head)");
  }
}

void useOwnShapes(const eng::Model& face, const PosedFace& posed, const LandmarkFrame& frame, Moved& moved,
                  std::vector<std::string>& taken, std::vector<std::string>& notes) {
  for (const OwnShape& own : kOwnShapes) {
    const std::string name(own.name);
    const std::vector<glm::vec3> deltas = worldDeltas(face, posed, moved.vertices, {&name, 1})[0];
    if (std::all_of(deltas.begin(), deltas.end(), [](const glm::vec3& d) { return d == glm::vec3(0.0f); })) continue;
    const bool halves = !own.right.empty();
    for (NamedDeltas& unit : moved.units) {
      const bool left = unit.name == own.left;
      if (!left && (!halves || unit.name != own.right)) continue;
      for (size_t k = 0; k < deltas.size(); ++k) {
        const float toLeft = glm::smoothstep(-kMidlineBlend, kMidlineBlend, frame.sideOf(moved.positions[k]));
        unit.deltas[k] = deltas[k] * (!halves ? 1.0f : left ? toLeft : 1.0f - toLeft);
      }
      taken.push_back(unit.name);
    }
    notes.push_back(halves ? std::string(own.left) + ", " + std::string(own.right) + ": the face's own " + name +
                                 ", split at the midline (not carried from the head)"
                           : std::string(own.left) + ": the face's own " + name + " (not carried from the head)");
  }
  useOwnArkitShapes(face, posed, moved, taken, notes);
}

bool faceHas(const eng::Model& face, std::string_view name, bool arkit) {
  const std::optional<uint32_t> shape = arkit ? facial::arkitIndex(name) : std::nullopt;
  for (const eng::Mesh& mesh : face.meshes)
    for (const std::string& existing : mesh.targetNames) {
      if (sameName(existing, name)) return true;
      if (shape && facial::arkitIndex(existing) == shape) return true;
    }
  return false;
}

// A new last target on mesh `mesh`: every weights channel animating it gets
// a zero weight for it in each key (in each of a cubic spline's triples).
void widenWeightChannels(eng::Model& model, size_t mesh) {
  for (eng::Animation& animation : model.animations)
    for (eng::WeightsChannel& channel : animation.channels) {
      if (channel.mesh != int(mesh) || channel.targetCount == 0) continue;
      const size_t n = channel.targetCount;
      std::vector<float> widened;
      widened.reserve(channel.values.size() / n * (n + 1));
      for (size_t i = 0; i + n <= channel.values.size(); i += n) {
        widened.insert(widened.end(), channel.values.begin() + long(i), channel.values.begin() + long(i + n));
        widened.push_back(0.0f);
      }
      channel.values = std::move(widened);
      channel.targetCount = n + 1;
    }
}

// Appends `target` to every mesh it moves: displacements into each vertex's
// mesh space, normal displacements from the smooth normals before and after.
// False when it moves no vertex more than `still` (nothing written).
// Rest normals as computeSmoothNormals gives them, per mesh and primitive,
// made once and shared by every target written.
using RestNormals = std::vector<std::vector<std::vector<glm::vec3>>>;

bool writeTarget(eng::Model& model, const PosedFace& posed, const Moved& moved, const NamedDeltas& target,
                 float still, RestNormals& restNormals) {
  std::vector<std::vector<size_t>> byMesh(model.meshes.size());
  bool written = false;
  for (size_t k = 0; k < moved.vertices.size(); ++k)
    if (glm::length(target.deltas[k]) > still)
      byMesh[posed.primitives[moved.vertices[k].primitive].mesh].push_back(k), written = true;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (byMesh[m].empty()) continue;
    eng::Mesh& mesh = model.meshes[m];
    std::vector<eng::MorphTarget> added(mesh.primitives.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) added[p].positions.assign(mesh.primitives[p].vertexCount(), glm::vec3(0.0f));
    for (size_t k : byMesh[m]) {
      const PosedPrimitive& pp = posed.primitives[moved.vertices[k].primitive];
      added[pp.primitive].positions[moved.vertices[k].vertex] = pp.toLocal(moved.vertices[k].vertex, target.deltas[k]);
    }
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      eng::Primitive& primitive = mesh.primitives[p];
      if (primitive.normals.size() != primitive.vertexCount()) continue;
      std::vector<glm::vec3> after(primitive.positions);
      bool any = false;
      for (size_t v = 0; v < after.size(); ++v) after[v] += added[p].positions[v], any = any || added[p].positions[v] != glm::vec3(0.0f);
      if (!any) continue;
      restNormals.resize(model.meshes.size());
      restNormals[m].resize(mesh.primitives.size());
      std::vector<glm::vec3>& before = restNormals[m][p];
      if (before.empty()) before = eng::computeSmoothNormals(primitive.positions, primitive.indices);
      const std::vector<glm::vec3> turned = eng::computeSmoothNormals(after, primitive.indices);
      added[p].normals.resize(after.size());
      for (size_t v = 0; v < after.size(); ++v) added[p].normals[v] = turned[v] - before[v];
    }
    for (size_t p = 0; p < mesh.primitives.size(); ++p) mesh.primitives[p].targets.push_back(std::move(added[p]));
    mesh.targetNames.push_back(target.name);
    mesh.defaultWeights.push_back(0.0f);
    widenWeightChannels(model, m);
  }
  return written;
}

}  // namespace

namespace {

// The ARKit 52 (those a face can have) over every vertex the units move:
// split from the units, the rest made from the face's geometry, in ARKit's
// order; what could not be made is named in `warnings`.
std::vector<NamedDeltas> arkitShapes(const Moved& moved, std::span<const FaceSurface* const> surfaces,
                                     std::span<const glm::vec3> skinNormals, const FaceLandmarks& steady,
                                     const LandmarkFrame& frame, const FaceParts& parts, std::vector<std::string>& warnings) {
  std::vector<std::string> fromGeometry, unmade;
  std::vector<NamedDeltas> shapes = arkitFromUnits(moved.units, moved.positions, frame, fromGeometry);
  std::vector<FacePart> vertexParts;  // in the order the units' vertices were appended
  for (const FaceSurface* surface : surfaces) vertexParts.insert(vertexParts.end(), surface->parts.begin(), surface->parts.end());
  std::vector<glm::vec3> normals(skinNormals.begin(), skinNormals.end());
  normals.resize(moved.positions.size(), glm::vec3(0.0f));
  const ShapeGeometry geometry{.positions = moved.positions, .parts = vertexParts, .normals = normals,
                               .landmarks = &steady, .frame = &frame, .faceParts = &parts};
  for (NamedDeltas& shape : arkitFromGeometry(fromGeometry, moved.units, geometry, unmade)) shapes.push_back(std::move(shape));
  std::stable_sort(shapes.begin(), shapes.end(), [](const NamedDeltas& a, const NamedDeltas& b) {
    return facial::arkitIndex(a.name).value_or(0) < facial::arkitIndex(b.name).value_or(0);
  });
  if (!unmade.empty()) {
    std::string line = std::to_string(unmade.size()) + " ARKit shapes were not made (the gaze shapes need eyeballs of the face's own, not eyes painted on its skin; the others their action unit or the jaw drop):";
    for (const std::string& name : unmade) line += " " + name;
    warnings.push_back(line);
  }
  return shapes;
}

// Both faces have skin to match, and the face no more than the transfer is bounded for.
eng::Result<void> checkSkin(const FaceSurface& src, const FaceSurface& tgt, const PosedFace& posed,
                            const TransferOptions& options) {
  if (src.triangles.empty())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: the source has no skin triangles (" +
                                                               std::to_string(src.positions.size()) + " skin vertices)");
  if (tgt.triangles.empty())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: the face has no skin triangles (" +
                                                               std::to_string(tgt.positions.size()) + " skin vertices of " +
                                                               std::to_string(posed.vertexCount()) + ")");
  if (tgt.positions.size() > options.maxSkinVertices)
    return eng::makeError(eng::ErrorKind::TooLarge,
                          "target transfer: the face has " + std::to_string(tgt.positions.size()) +
                              " skin vertices, more than " + std::to_string(options.maxSkinVertices) +
                              ": simplify it first (a face reads at 10-50k)");
  return {};
}

}  // namespace

eng::Result<TransferResult> transferTargets(const SourceFace& source, const eng::Model& face, const PosedFace& posed,
                                            const FaceLandmarks& landmarks, const FaceParts& parts,
                                            const TransferOptions& options) {
  if (!source.model) return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: no source face");
  ENG_TRY(checkLandmarks(source.landmarks, "source"));
  ENG_TRY(checkLandmarks(landmarks, "face"));
  const std::vector<std::string> units = sourceUnits(*source.model);
  if (units.empty()) {
    size_t targets = 0;
    for (const eng::Mesh& mesh : source.model->meshes) targets += mesh.targetNames.size();
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "target transfer: the source has no action units (AU... targets) among its " +
                              std::to_string(targets) + " targets on " + std::to_string(source.model->meshes.size()) + " meshes");
  }
  const FaceSurface src = gatherSurface(*source.model, source.posed, source.parts, {FacePart::Skin});
  const FaceSurface tgt = gatherSurface(face, posed, parts, {FacePart::Skin, FacePart::Lashes, FacePart::Brows});
  ENG_TRY(checkSkin(src, tgt, posed, options));
  ENG_TRY(checkOnSurface(tgt, landmarks, LandmarkFrame(landmarks)));
  ENG_TRY(checkFacing(source, landmarks));
  const FaceLandmarks steady = withSteadyMouthCorners(source.landmarks, landmarks);
  const LandmarkFrame frame(steady);
  const BrowBand brows = findBrows(face, posed, tgt, steady);
  eng::Result<Correspondence> matched = correspond(src, source.landmarks, tgt, steady);
  if (!matched) return matched.error().prefixed("target transfer: ");
  const Correspondence corr = std::move(*matched);
  const FaceSurface jaw = gatherSurface(face, posed, parts, {FacePart::LowerTeeth, FacePart::Tongue});
  Moved moved = carryUnits(source, src, tgt, jaw, corr, units, steady, parts, brows);
  const FaceSurface onSkin = gatherSurface(face, posed, parts, {FacePart::SkinLayer});
  const std::vector<glm::vec3> tgtNormals = skinNormals(tgt);
  appendOnSkin(moved, onSkin, tgt, tgtNormals, frame.eyeSpan());
  // The eyeballs: no unit moves them, the gaze shapes turn them. The upper
  // teeth neither, but a face's own shape may (useOwnShapes).
  const FaceSurface still = gatherSurface(face, posed, parts, {FacePart::EyeballRight, FacePart::EyeballLeft, FacePart::UpperTeeth});
  appendStill(moved, still);

  TransferResult result{.model = face, .report = {}};
  TransferReport& report = result.report;
  useOwnShapes(face, posed, frame, moved, report.own, report.notes);
  if (brows.found()) report.notes.push_back(browsNote(brows));
  std::vector<NamedDeltas> made;
  if (options.actionUnits)
    for (const NamedDeltas& unit : moved.units) made.push_back(unit);
  if (options.arkit) {
    const std::array<const FaceSurface*, 4> surfaces{&tgt, &jaw, &onSkin, &still};
    for (NamedDeltas& shape : arkitShapes(moved, surfaces, tgtNormals, steady, frame, parts, report.warnings))
      made.push_back(std::move(shape));
  }
  RestNormals restNormals;
  for (const NamedDeltas& target : made) {
    if (faceHas(face, target.name, !target.name.starts_with("AU"))) {
      report.kept.push_back(target.name);
      continue;
    }
    if (writeTarget(result.model, posed, moved, target, kStillShare * frame.eyeSpan(), restNormals))
      report.made.push_back(target.name);
  }
  if (options.actionUnits && options.detailLayers) {
    DetailTransferReport details = carryDetailLayers(source, src, tgt, corr, posed, result.model);
    report.details = std::move(details.carried);
    for (std::string& warning : details.warnings) report.warnings.push_back(std::move(warning));
  }
  if (jaw.positions.empty()) report.warnings.push_back("no lower teeth or tongue found: the jaw units move the skin only");
  if (!(parts.eyeRadii[0] > 0.0f) || !(parts.eyeRadii[1] > 0.0f))
    report.warnings.push_back("no eyeball size known: the lids follow the source's without sliding over the eyes");
  return result;
}

}  // namespace autorig
