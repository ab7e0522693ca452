#include "bake/head/skin_surface.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include <glm/common.hpp>

#include "bake/head/eye_opening.h"

namespace bake {
namespace {

using glm::vec2;
using glm::vec3;

double rad(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Samples lo..hi so that neighbouring samples are `spacing(x)` apart (n + 1
// samples, n rounded to even when asked so a symmetric spacing puts a sample
// on the middle).
std::vector<double> distribute(double lo, double hi, const std::function<double(double)>& spacing, bool even) {
  const int steps = 40000;
  const double h = (hi - lo) / steps;
  std::vector<double> cdf(steps + 1, 0.0);
  for (int k = 0; k < steps; ++k) cdf[k + 1] = cdf[k] + h / spacing(lo + (k + 0.5) * h);
  int n = std::max(2, static_cast<int>(std::lround(cdf.back())));
  if (even && n % 2) ++n;
  std::vector<double> out(n + 1);
  int k = 0;
  for (int i = 0; i <= n; ++i) {
    const double target = cdf.back() * i / n;
    while (k < steps - 1 && cdf[k + 1] < target) ++k;
    const double span = cdf[k + 1] - cdf[k];
    const double f = span > 0 ? std::clamp((target - cdf[k]) / span, 0.0, 1.0) : 0.0;
    out[i] = lo + (k + f) * h;
  }
  out.front() = lo;
  out.back() = hi;
  return out;
}

vec3 gridDirection(double azimuth, double elevation) {
  return vec3(static_cast<float>(std::cos(elevation) * std::sin(azimuth)), static_cast<float>(std::sin(elevation)),
              static_cast<float>(std::cos(elevation) * std::cos(azimuth)));
}

vec2 anglesFrom(const vec3& centre, const vec3& p) {
  const vec3 d = p - centre;
  return vec2(std::atan2(d.x, d.z), std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z)));
}

vec3 slerp(const vec3& a, const vec3& b, float t) {
  const float c = std::clamp(glm::dot(a, b), -1.0f, 1.0f);
  const float angle = std::acos(c);
  if (angle < 1e-5f) return glm::normalize(glm::mix(a, b, t));
  const float s = std::sin(angle);
  return glm::normalize(a * (std::sin((1 - t) * angle) / s) + b * (std::sin(t * angle) / s));
}

constexpr uint32_t kNone = 0xffffffffu;

// Index ranges of the grid rectangle replaced by an eyelid patch (vertex
// indices, inclusive; the border vertices stay grid vertices).
struct PatchRect {
  int i0, i1, j0, j1;
  bool containsCell(int i, int j) const { return i >= i0 && i < i1 && j >= j0 && j < j1; }
  bool strictlyInside(int i, int j) const { return i > i0 && i < i1 && j > j0 && j < j1; }
};

class SkinBuilder {
 public:
  SkinBuilder(const HeadProportions& p, const HeadSdf& sdf) : prop_(p), sdf_(sdf) {}

  eng::Result<SkinSurface> build() {
    layoutGrid();
    placeEyeRects();
    if (auto r = castGrid(); !r) return r.error();
    stitchGrid();
    for (float side : {1.0f, -1.0f})
      if (auto r = buildEyelidPatch(side); !r) return r.error();
    buildMouthPocket();
    out_.gridAngles.reserve(out_.positions.size());
    for (const vec3& p : out_.positions) out_.gridAngles.push_back(anglesFrom(prop_.gridCentre, p));
    return std::move(out_);
  }

 private:
  uint32_t addVertex(const vec3& p, const vec2& uv, SkinPart part, uint32_t weldId = kNone) {
    const uint32_t v = static_cast<uint32_t>(out_.positions.size());
    out_.positions.push_back(p);
    out_.uvs.push_back(uv);
    out_.weldIds.push_back(weldId == kNone ? v : weldId);
    out_.parts.push_back(part);
    out_.jawSide.push_back(0.0f);
    out_.eyeSide.push_back(0.0f);
    out_.lidRing.push_back(0.0f);
    out_.upperLid.push_back(0.0f);
    out_.mouthDepth.push_back(0.0f);
    return v;
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) {
    out_.indices.insert(out_.indices.end(), {a, b, c});
  }

  // --- grid layout ---------------------------------------------------------
  void layoutGrid() {
    // Columns: dense over the face, sparse at the back of the head.
    azimuths_ = distribute(-std::numbers::pi, std::numbers::pi, [](double a) {
      return rad(1.12 + (5.0 - 1.12) * glm::smoothstep(rad(38), rad(110), std::abs(a)));
    }, true);
    // Rows: dense from chin to brow, denser still across the lips.
    const double seam = sdf_.seamElevation();
    elevations_ = distribute(-std::numbers::pi / 2, std::numbers::pi / 2, [seam](double e) {
      double s;
      if (e > 0) {
        s = 1.0 + (4.5 - 1.0) * glm::smoothstep(rad(50), rad(78), e);
      } else {
        // Down the neck the rays meet the skin at a grazing angle: at the
        // front of the neck (2 cm in front of the grid's centre) one degree
        // is up to 9 mm of skin, and rows 4 degrees apart left the neck's cut
        // edge a zigzag. Rows about 3 mm apart there, to just past the cut
        // (82 degrees at the front); the flat underside behind it stays sparse.
        const double c = std::cos(e);
        s = std::clamp(7.8 * c * c, 0.3, 1.0);
        s += (4.5 - s) * glm::smoothstep(rad(82), rad(86), -e);
      }
      const double lips = 1.0 - glm::smoothstep(rad(5.5), rad(8.5), std::abs(e - seam));
      s = s + (0.55 - s) * lips;
      return rad(s);
    }, false);
    // Put one row exactly on the seam cone, shifting its neighbours smoothly.
    seamRow_ = 0;
    for (int j = 0; j < rows(); ++j)
      if (std::abs(elevations_[j] - seam) < std::abs(elevations_[seamRow_] - seam)) seamRow_ = j;
    const double shift = seam - elevations_[seamRow_];
    for (int j = 1; j < rows(); ++j)
      elevations_[j] += shift * std::max(0.0, 1.0 - std::abs(j - seamRow_) / 8.0);
    // Mouth corners: the columns nearest the corner azimuth.
    const int mid = cols() / 2;
    cornerL_ = mid;
    for (int i = mid; i < cols(); ++i)
      if (std::abs(azimuths_[i] - sdf_.mouthCornerAzimuth()) < std::abs(azimuths_[cornerL_] - sdf_.mouthCornerAzimuth()))
        cornerL_ = i;
    cornerR_ = cols() - cornerL_;
  }
  int cols() const { return static_cast<int>(azimuths_.size()) - 1; }  // column cols() repeats column 0
  int rows() const { return static_cast<int>(elevations_.size()) - 1; }  // rows 0 and rows() are the poles

  int nearestColumn(double azimuth) const {
    int best = 0;
    for (int i = 0; i <= cols(); ++i)
      if (std::abs(azimuths_[i] - azimuth) < std::abs(azimuths_[best] - azimuth)) best = i;
    return best;
  }
  int nearestRow(double elevation) const {
    int best = 0;
    for (int j = 0; j <= rows(); ++j)
      if (std::abs(elevations_[j] - elevation) < std::abs(elevations_[best] - elevation)) best = j;
    return best;
  }

  void placeEyeRects() {
    // Bound the left eye's lid edge as seen from the grid centre, then pad.
    const EyeOpening eye(prop_, 1.0f);
    vec2 lo(1e9f), hi(-1e9f);
    for (int k = 0; k <= 64; ++k) {
      const float t = k / 64.0f;
      for (const vec2& a : {eye.upperLid(t), eye.lowerLid(t)}) {
        const vec3 p = eye.centre() + eye.direction(a) * eye.radius();
        const vec2 g = anglesFrom(prop_.gridCentre, p);
        lo = glm::min(lo, g);
        hi = glm::max(hi, g);
      }
    }
    PatchRect left;
    left.i0 = nearestColumn(lo.x - rad(4.5));
    left.i1 = nearestColumn(hi.x + rad(10.0));
    left.j0 = nearestRow(lo.y - rad(8.0));
    left.j1 = nearestRow(hi.y + rad(9.0));
    PatchRect right = left;
    right.i0 = cols() - left.i1;
    right.i1 = cols() - left.i0;
    eyeRects_[0] = left;
    eyeRects_[1] = right;
  }

  bool insideEyeRect(int i, int j) const {
    return eyeRects_[0].strictlyInside(i, j) || eyeRects_[1].strictlyInside(i, j);
  }
  bool onSeam(int i, int j) const { return j == seamRow_ && i > cornerR_ && i < cornerL_; }

  // --- grid vertices -------------------------------------------------------
  eng::Result<void> castGrid() {
    const int nc = cols(), nr = rows();
    grid_.assign(static_cast<size_t>((nc + 1) * (nr + 1)), kNone);
    lowerSeam_.assign(static_cast<size_t>(nc + 1), kNone);
    const vec3 c = prop_.gridCentre;
    auto cast = [&](double az, double el) -> std::optional<vec3> { return sdf_.castOut(c, gridDirection(az, el)); };

    const std::optional<vec3> bottom = cast(0.0, -std::numbers::pi / 2), top = cast(0.0, std::numbers::pi / 2);
    if (!bottom || !top) return eng::makeError(eng::ErrorKind::Malformed, "head skin: rays from the grid centre miss the crown or the neck");
    // One pole vertex per column (welded for normals): each pole triangle
    // then covers only its own column of texture, which keeps the sampler's
    // mip selection sane at the crown instead of averaging the whole image.
    for (int i = 0; i < nc; ++i) {
      const float u = (i + 0.5f) / nc;
      bottomPoles_.push_back(addVertex(*bottom, vec2(u, rowV(0.0)), SkinPart::Skin, i ? bottomPoles_[0] : kNone));
      topPoles_.push_back(addVertex(*top, vec2(u, rowV(1.0)), SkinPart::Skin, i ? topPoles_[0] : kNone));
      out_.jawSide[bottomPoles_.back()] = 1.0f;
    }

    const double seam = sdf_.seamElevation();
    const double corner = azimuths_[cornerL_];
    for (int j = 1; j < nr; ++j) {
      for (int i = 0; i < nc; ++i) {
        if (insideEyeRect(i, j)) continue;
        const std::optional<vec3> hit = cast(azimuths_[i], elevations_[j]);
        if (!hit)
          return eng::makeError(eng::ErrorKind::Malformed, "head skin: grid ray (column " + std::to_string(i) + ", row " + std::to_string(j) +
                                ") found no surface");
        const vec2 uv(float(i) / nc, rowV(double(j) / nr));
        const uint32_t v = addVertex(*hit, uv, SkinPart::Skin);
        grid_[index(i, j)] = v;
        // Jaw side: a clean split across the lips, widening into a soft
        // blend beyond the corners.
        const double lateral = std::max(0.0, std::abs(azimuths_[i]) - corner);
        const double band = 1e-4 + 0.55 * lateral;
        float jaw = static_cast<float>(glm::smoothstep(seam + band, seam - band, elevations_[j]));
        if (j == seamRow_ && (i == cornerL_ || i == cornerR_)) jaw = 0.5f;
        out_.jawSide[v] = jaw;
        if (onSeam(i, j)) {
          out_.jawSide[v] = 0.0f;
          const uint32_t lower = addVertex(*hit, uv, SkinPart::Skin);
          out_.jawSide[lower] = 1.0f;
          lowerSeam_[i] = lower;
        }
      }
      // Column nc repeats column 0 with u = 1 (texture seam at the back).
      const uint32_t first = grid_[index(0, j)];
      const uint32_t wrap = addVertex(out_.positions[first], vec2(1.0f, out_.uvs[first].y), SkinPart::Skin, first);
      out_.jawSide[wrap] = out_.jawSide[first];
      grid_[index(nc, j)] = wrap;
    }
    return {};
  }
  size_t index(int i, int j) const { return static_cast<size_t>(j * (cols() + 1) + i); }

  // Vertex at grid (i, j) as seen from a cell on side `above` of the seam.
  uint32_t at(int i, int j, bool cellAboveSeam) const {
    if (j == 0) return bottomPoles_[static_cast<size_t>(i % cols())];
    if (j == rows()) return topPoles_[static_cast<size_t>(i % cols())];
    if (onSeam(i, j) && !cellAboveSeam) return lowerSeam_[i];
    return grid_[index(i, j)];
  }

  void stitchGrid() {
    for (int j = 0; j < rows(); ++j) {
      for (int i = 0; i < cols(); ++i) {
        if (eyeRects_[0].containsCell(i, j) || eyeRects_[1].containsCell(i, j)) continue;
        const bool above = j >= seamRow_;  // the cell's bottom edge is on or above the seam row
        const uint32_t a = at(i, j, above), b = at(i + 1, j, above);
        const uint32_t c = at(i + 1, j + 1, above), d = at(i, j + 1, above);
        if (j == 0) {
          tri(a, c, d);  // a: this column's bottom pole vertex
        } else if (j == rows() - 1) {
          tri(a, b, d);  // d: this column's top pole vertex
        } else {
          // Split along the shorter diagonal for a smoother surface.
          const vec3 &pa = out_.positions[a], &pb = out_.positions[b], &pc = out_.positions[c],
                     &pd = out_.positions[d];
          if (glm::length(pa - pc) <= glm::length(pb - pd)) {
            tri(a, b, c);
            tri(a, c, d);
          } else {
            tri(a, b, d);
            tri(b, c, d);
          }
        }
      }
    }
  }

  // Texture v of a row fraction (0 = bottom pole, 1 = top pole). The crown
  // and the neck's base sit a few texels in from the image edges, so a
  // repeating sampler never blends hair into the neck or back.
  static float rowV(double rowFraction) {
    constexpr double kMargin = 0.006;
    return static_cast<float>(kMargin + (1.0 - 2.0 * kMargin) * (1.0 - rowFraction));
  }

  // Texture coordinate the grid would give a point: its direction from the
  // grid centre, mapped through the column/row angle tables.
  vec2 gridUv(const vec3& p) const {
    const vec2 a = anglesFrom(prop_.gridCentre, p);
    auto fractionalIndex = [](const std::vector<double>& table, double x) {
      const auto it = std::upper_bound(table.begin(), table.end(), x);
      if (it == table.begin()) return 0.0;
      if (it == table.end()) return double(table.size() - 1);
      const size_t i = size_t(it - table.begin()) - 1;
      return i + (x - table[i]) / (table[i + 1] - table[i]);
    };
    return vec2(static_cast<float>(fractionalIndex(azimuths_, a.x) / cols()),
                rowV(fractionalIndex(elevations_, a.y) / rows()));
  }

  // --- eyelids ---------------------------------------------------------------
  // Rings cast onto the surface between the patch border and the lid edge.
  static constexpr int kLidCastRings = 12;

  // Lid thickness at margin angles a: the lower lid's below the eye's
  // middle, the upper lid's above, blended smoothly across it.
  float lidThickness(const EyeOpening& eye, const vec2& a) const {
    const float t = static_cast<float>(glm::smoothstep(-6.0, 6.0, static_cast<double>(a.y - eye.middle().y)));
    return prop_.lowerLidThickness + (prop_.upperLidThickness - prop_.lowerLidThickness) * t;
  }
  // Angles a moved `degrees` further out from the eye's middle (in the
  // almond's scaled coordinates): the lid edge lies past the margin.
  static vec2 pushedOut(const EyeOpening& eye, const vec2& a, float degrees) {
    const vec2 q = (a - eye.middle()) / eye.halfExtent();
    const float len = glm::length(q);
    return len > 0 ? a + (q / len) * degrees : a;
  }

  // The eye patch's border loop, counter-clockwise seen from the front.
  std::vector<uint32_t> eyePatchBorder(const PatchRect& r) const {
    std::vector<uint32_t> ring0;
    for (int i = r.i0; i < r.i1; ++i) ring0.push_back(grid_[index(i, r.j0)]);
    for (int j = r.j0; j < r.j1; ++j) ring0.push_back(grid_[index(r.i1, j)]);
    for (int i = r.i1; i > r.i0; --i) ring0.push_back(grid_[index(i, r.j1)]);
    for (int j = r.j1; j > r.j0; --j) ring0.push_back(grid_[index(r.i0, j)]);
    return ring0;
  }

  // Ring positions: 0 = border, 1..kLidCastRings cast onto the head's
  // surface, then the lid edge, the margin (inside the eyeball) and a tucked
  // ring. `margin` holds each border vertex's margin angles.
  std::vector<std::vector<vec3>> eyelidRingPositions(const EyeOpening& eye, const std::vector<uint32_t>& ring0,
                                                     const std::vector<vec2>& margin) const {
    const size_t n = ring0.size();
    const vec3 e = eye.centre();
    const vec3 castOrigin = e - vec3(0.0f, 0.0f, 0.007f);
    const float rEye = eye.radius();
    std::vector<std::vector<vec3>> ringPos;
    ringPos.push_back({});
    for (size_t s = 0; s < n; ++s) ringPos[0].push_back(out_.positions[ring0[s]]);
    std::vector<vec3> edge(n), inner(n), tucked(n);
    for (size_t s = 0; s < n; ++s) {
      const vec2 edgeAngles = pushedOut(eye, margin[s], 2.2f);
      edge[s] = e + eye.direction(edgeAngles) * (rEye + 0.85f * lidThickness(eye, edgeAngles));
      inner[s] = e + eye.direction(margin[s]) * (rEye - 0.0004f);
      tucked[s] = e + eye.direction(glm::mix(margin[s], eye.middle(), 0.45f)) * (rEye - 0.0015f);
    }
    for (int k = 1; k <= kLidCastRings; ++k) {
      const float w = spokeParameter(float(k) / (kLidCastRings + 1));
      std::vector<vec3> ring(n);
      for (size_t s = 0; s < n; ++s) {
        const vec3 d0 = glm::normalize(ringPos[0][s] - castOrigin);
        const vec3 d1 = glm::normalize(edge[s] - castOrigin);
        const vec3 dir = slerp(d0, d1, w);
        const std::optional<vec3> hit = sdf_.castOut(castOrigin, dir, 0.08f);
        ring[s] = hit ? *hit : glm::mix(ringPos[0][s], edge[s], w);
      }
      ringPos.push_back(std::move(ring));
    }
    relaxPatch(ringPos, edge, kLidCastRings);
    ringPos.push_back(edge);
    ringPos.push_back(inner);
    ringPos.push_back(tucked);
    return ringPos;
  }

  // Adds the vertices of every ring after the border (which exists already)
  // and marks all of them with their eye, lid and lid ring (0 at the border,
  // 1 at the lid edge, above 1 inside it). Returns each ring's vertex ids.
  // Texture coordinates continue the grid's own mapping (the direction seen
  // from the grid centre), so the lids get as many texels as the skin around.
  std::vector<std::vector<uint32_t>> addEyelidVertices(const std::vector<std::vector<vec3>>& ringPos,
                                                       const std::vector<uint32_t>& ring0, const std::vector<bool>& upper,
                                                       float side) {
    const size_t n = ring0.size();
    const size_t edgeRing = ringPos.size() - 3;
    std::vector<std::vector<uint32_t>> ringIds(ringPos.size());
    ringIds[0] = ring0;
    for (size_t s = 0; s < n; ++s) {
      out_.eyeSide[ring0[s]] = side;
      out_.upperLid[ring0[s]] = upper[s] ? 1.0f : 0.0f;
    }
    std::vector<float> spokeLength(n, 0.0f);
    for (size_t s = 0; s < n; ++s)
      for (size_t k = 1; k <= edgeRing; ++k) spokeLength[s] += glm::length(ringPos[k][s] - ringPos[k - 1][s]);
    std::vector<float> travelled(n, 0.0f);
    for (size_t k = 1; k < ringPos.size(); ++k) {
      for (size_t s = 0; s < n; ++s) {
        float f;
        if (k <= edgeRing) {
          travelled[s] += glm::length(ringPos[k][s] - ringPos[k - 1][s]);
          f = travelled[s] / spokeLength[s];
        } else {
          f = 1.0f + 0.25f * float(k - edgeRing);
        }
        const uint32_t v = addVertex(ringPos[k][s], gridUv(ringPos[k][s]), SkinPart::Skin);
        out_.eyeSide[v] = side;
        out_.lidRing[v] = f;
        out_.upperLid[v] = upper[s] ? 1.0f : 0.0f;
        ringIds[k].push_back(v);
      }
    }
    return ringIds;
  }

  // Quads between neighbouring rings, then a fan closing the innermost ring
  // on a centre vertex set deepest into the eye.
  void stitchEyelidRings(const std::vector<std::vector<uint32_t>>& ringIds, const EyeOpening& eye, float side) {
    const size_t n = ringIds[0].size();
    for (size_t k = 0; k + 1 < ringIds.size(); ++k)
      for (size_t s = 0; s < n; ++s) {
        const size_t t = (s + 1) % n;
        const uint32_t a = ringIds[k][s], b = ringIds[k][t], c = ringIds[k + 1][t], d = ringIds[k + 1][s];
        tri(a, b, c);
        tri(a, c, d);
      }
    const vec3 centrePos = eye.centre() + eye.direction(eye.middle()) * (eye.radius() - 0.0025f);
    const uint32_t centre = addVertex(centrePos, gridUv(centrePos), SkinPart::Skin);
    out_.eyeSide[centre] = side;
    out_.lidRing[centre] = 2.0f;
    for (size_t s = 0; s < n; ++s) tri(ringIds.back()[s], ringIds.back()[(s + 1) % n], centre);
  }

  // Landmark features on the lid edge, named "<name>.<feature>".
  void addEyelidFeatures(const EyeOpening& eye, const std::string& name) {
    const vec3 e = eye.centre();
    const float rEye = eye.radius();
    auto edgePoint = [&](const vec2& a) {
      return e + eye.direction(pushedOut(eye, a, 2.2f)) * (rEye + 0.85f * lidThickness(eye, a));
    };
    out_.features[name + ".centre"] = e;
    out_.features[name + ".inner_corner"] = edgePoint(eye.upperLid(0.0f));
    out_.features[name + ".outer_corner"] = edgePoint(eye.upperLid(1.0f));
    // Lid edge points at tenths of the way from the inner corner (upper and
    // lower at one fraction share their lateral angle, so a blink can move
    // one straight onto the other), plus names for the middle and quarters.
    for (int k = 1; k <= 9; ++k) {
      const float t = k / 10.0f;
      const std::string at = "@0." + std::to_string(k);
      out_.features[name + ".upper_lid" + at] = edgePoint(eye.upperLid(t));
      out_.features[name + ".lower_lid" + at] = edgePoint(eye.lowerLid(t));
    }
    out_.features[name + ".upper_lid"] = edgePoint(eye.upperLid(0.5f));
    out_.features[name + ".upper_lid_inner"] = edgePoint(eye.upperLid(0.25f));
    out_.features[name + ".upper_lid_outer"] = edgePoint(eye.upperLid(0.75f));
    out_.features[name + ".lower_lid"] = edgePoint(eye.lowerLid(0.5f));
    out_.features[name + ".lower_lid_inner"] = edgePoint(eye.lowerLid(0.25f));
    out_.features[name + ".lower_lid_outer"] = edgePoint(eye.lowerLid(0.75f));
  }

  // The eyelid patch of one eye: rings from the grid's eye hole in to the lid
  // edge and on into the eyeball, where the eyeball mesh hides them.
  eng::Result<void> buildEyelidPatch(float side) {
    const EyeOpening eye(prop_, side);
    const std::vector<uint32_t> ring0 = eyePatchBorder(eyeRects_[side > 0 ? 0 : 1]);
    // Per border vertex: margin angles and whether it is on the upper lid.
    std::vector<vec2> margin(ring0.size());
    std::vector<bool> upper(ring0.size());
    for (size_t s = 0; s < ring0.size(); ++s) {
      bool up = true;
      margin[s] = eye.marginAt(eye.polarAngle(eye.angles(out_.positions[ring0[s]] - eye.centre())), &up);
      upper[s] = up;
    }
    const std::vector<std::vector<vec3>> ringPos = eyelidRingPositions(eye, ring0, margin);
    stitchEyelidRings(addEyelidVertices(ringPos, ring0, upper, side), eye, side);
    addEyelidFeatures(eye, side > 0 ? "eye_L" : "eye_R");
    return {};
  }

  // Where ring t in [0, 1] sits along a spoke from the patch border to the lid
  // edge: dense at both ends, so the first rings match the grid's cell size
  // and the last ones resolve the lid edge.
  static float spokeParameter(float t) {
    constexpr float kPi2 = 6.28318530718f;
    return t - 0.72f * std::sin(kPi2 * t) / kPi2;
  }

  // Evens out the cast rings (spokes from a rectangle to an almond can bunch
  // or cross near the rectangle's corners): smoothing along each ring and
  // along each spoke toward its intended spacing, then back onto the surface.
  void relaxPatch(std::vector<std::vector<vec3>>& rings, const std::vector<vec3>& edge, int castRings) const {
    const size_t n = rings[0].size();
    std::vector<float> target(castRings + 2);  // intended spoke parameter per ring
    for (int k = 0; k <= castRings + 1; ++k) target[k] = spokeParameter(float(k) / (castRings + 1));
    auto ringAt = [&](int k, size_t s) -> const vec3& { return k <= castRings ? rings[k][s] : edge[s]; };
    for (int iteration = 0; iteration < 30; ++iteration) {
      std::vector<std::vector<vec3>> next = rings;
      for (int k = 1; k <= castRings; ++k) {
        const float wIn = 1.0f / (target[k] - target[k - 1]), wOut = 1.0f / (target[k + 1] - target[k]);
        for (size_t s = 0; s < n; ++s) {
          const vec3& p = rings[k][s];
          const vec3 alongRing = 0.5f * (rings[k][(s + n - 1) % n] + rings[k][(s + 1) % n]);
          const vec3 alongSpoke = (wIn * ringAt(k - 1, s) + wOut * ringAt(k + 1, s)) / (wIn + wOut);
          // Rings near the rectangular border keep its corners (rounding them
          // there folds the first quads); inner rings round off freely.
          const float round = 0.5f * std::pow(float(k) / castRings, 1.5f);
          vec3 q = p + 0.5f * (round * alongRing + (1.0f - round) * alongSpoke - p);
          for (int step = 0; step < 3; ++step) q -= sdf_.distance(q) * sdf_.normal(q);
          next[k][s] = q;
        }
      }
      rings.swap(next);
    }
  }

  // --- mouth pocket -----------------------------------------------------------
  void buildMouthPocket() {
    // Seam loop with the skin on its left: upper side from the right corner to
    // the left one, then the lower side back.
    struct SeamPoint {
      uint32_t skin;
      float side;  // +1 upper, -1 lower, 0 corner
    };
    std::vector<SeamPoint> loop;
    loop.push_back({grid_[index(cornerR_, seamRow_)], 0.0f});
    for (int i = cornerR_ + 1; i < cornerL_; ++i) loop.push_back({grid_[index(i, seamRow_)], 1.0f});
    loop.push_back({grid_[index(cornerL_, seamRow_)], 0.0f});
    for (int i = cornerL_ - 1; i > cornerR_; --i) loop.push_back({lowerSeam_[i], -1.0f});
    const size_t n = loop.size();
    const float halfWidth = std::max(std::abs(out_.positions[loop[0].skin].x), 1e-3f);

    // Ring shapes behind the seam: depth, half-height, width scale (metres).
    struct Ring {
      float depth, height, width;
    };
    static constexpr Ring kRings[] = {{0.0012f, 0.0012f, 0.97f}, {0.0035f, 0.0050f, 0.96f},
                                      {0.0070f, 0.0105f, 1.00f}, {0.0120f, 0.0140f, 1.04f},
                                      {0.0180f, 0.0155f, 1.04f}, {0.0250f, 0.0145f, 0.95f},
                                      {0.0310f, 0.0110f, 0.80f}, {0.0360f, 0.0060f, 0.50f}};
    constexpr size_t kRingCount = sizeof(kRings) / sizeof(kRings[0]);

    std::vector<uint32_t> prev(n);
    for (size_t s = 0; s < n; ++s) {
      const uint32_t skin = loop[s].skin;
      const uint32_t v = addVertex(out_.positions[skin], vec2(0.5f, 0.0f), SkinPart::MouthInterior, out_.weldIds[skin]);
      out_.jawSide[v] = out_.jawSide[skin];
      prev[s] = v;
    }
    for (size_t k = 0; k < kRingCount; ++k) {
      std::vector<uint32_t> ring(n);
      const float depthFraction = float(k + 1) / (kRingCount + 1);
      for (size_t s = 0; s < n; ++s) {
        const vec3 p = out_.positions[loop[s].skin];
        const float across = std::clamp(std::abs(p.x) / halfWidth, 0.0f, 1.0f);
        const float profile = std::pow(std::max(0.0f, 1.0f - across * across), 0.35f);
        const vec3 q(p.x * kRings[k].width, p.y + loop[s].side * kRings[k].height * profile, p.z - kRings[k].depth);
        const uint32_t v = addVertex(q, vec2(0.5f, depthFraction), SkinPart::MouthInterior);
        out_.jawSide[v] = loop[s].side > 0 ? 0.0f : (loop[s].side < 0 ? 1.0f : 0.5f);
        out_.mouthDepth[v] = depthFraction;
        ring[s] = v;
      }
      for (size_t s = 0; s < n; ++s) {
        const size_t t = (s + 1) % n;
        tri(prev[t], prev[s], ring[s]);
        tri(prev[t], ring[s], ring[t]);
      }
      prev = ring;
    }
    const vec3 seamMid = out_.positions[grid_[index(cols() / 2, seamRow_)]];
    const uint32_t back = addVertex(seamMid - vec3(0.0f, 0.0f, 0.039f), vec2(0.5f, 1.0f), SkinPart::MouthInterior);
    out_.jawSide[back] = 0.5f;
    out_.mouthDepth[back] = 1.0f;
    for (size_t s = 0; s < n; ++s) tri(prev[(s + 1) % n], prev[s], back);

    out_.features["mouth.corner_L"] = out_.positions[grid_[index(cornerL_, seamRow_)]];
    out_.features["mouth.corner_R"] = out_.positions[grid_[index(cornerR_, seamRow_)]];
    out_.features["mouth.seam_centre"] = seamMid;
  }

  const HeadProportions& prop_;
  const HeadSdf& sdf_;
  SkinSurface out_;
  std::vector<double> azimuths_, elevations_;
  int seamRow_ = 0, cornerL_ = 0, cornerR_ = 0;
  PatchRect eyeRects_[2]{};
  std::vector<uint32_t> grid_, lowerSeam_;
  std::vector<uint32_t> bottomPoles_, topPoles_;
};

}  // namespace

eng::Result<SkinSurface> buildSkinSurface(const HeadProportions& proportions, const HeadSdf& sdf) {
  return SkinBuilder(proportions, sdf).build();
}

}  // namespace bake
