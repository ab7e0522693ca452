#include "bake/head/skin_painter.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>

#include "engine/core/uv_raster.h"
#include "bake/head/value_noise.h"

namespace bake {
namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;

float gauss(float d, float width) { return std::exp(-(d * d) / (width * width)); }
float gauss2(const vec2& d, float width) { return std::exp(-glm::dot(d, d) / (width * width)); }

// A polyline through Catmull-Rom interpolated keys, for brow and crease curves.
class Curve2 {
 public:
  template <size_t N>
  explicit Curve2(const std::array<vec2, N>& keys, int samplesPerSpan = 16) {
    for (size_t i = 0; i + 1 < N; ++i) {
      const vec2 p0 = keys[i == 0 ? 0 : i - 1], p1 = keys[i], p2 = keys[i + 1], p3 = keys[std::min(i + 2, N - 1)];
      for (int k = 0; k < samplesPerSpan; ++k) {
        const float t = float(k) / samplesPerSpan, t2 = t * t, t3 = t2 * t;
        points_.push_back(0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                                  (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3));
      }
    }
    points_.push_back(keys[N - 1]);
    min_ = max_ = points_[0];
    for (const vec2& p : points_) {
      min_ = glm::min(min_, p);
      max_ = glm::max(max_, p);
    }
  }
  vec2 pointAt(float t) const {
    const float x = std::clamp(t, 0.0f, 1.0f) * float(points_.size() - 1);
    const size_t i = std::min(points_.size() - 2, static_cast<size_t>(x));
    return glm::mix(points_[i], points_[i + 1], x - float(i));
  }
  // Nearest point: curve parameter t in [0, 1] and signed distance (+ to the left of travel).
  bool nearest(const vec2& q, float reach, float& t, float& signedDistance) const {
    if (q.x < min_.x - reach || q.x > max_.x + reach || q.y < min_.y - reach || q.y > max_.y + reach) return false;
    float best = 1e9f;
    const size_t n = points_.size() - 1;
    for (size_t i = 0; i < n; ++i) {
      const vec2 a = points_[i], ab = points_[i + 1] - a;
      const float f = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
      const vec2 d = q - (a + ab * f);
      const float dist = glm::length(d);
      if (dist < best) {
        best = dist;
        t = (float(i) + f) / float(n);
        signedDistance = (ab.x * d.y - ab.y * d.x) >= 0.0f ? dist : -dist;
      }
    }
    return best <= reach;
  }

 private:
  std::vector<vec2> points_;
  vec2 min_, max_;
};

// Left brow, front projection (x, y); the right brow mirrors it.
const Curve2& browCurve() {
  // On the orbital rim, a flat arch: brows set high above the lids made the
  // face look permanently surprised, and every brow-raising state read as surprise.
  // The heads start a few millimetres inside the inner eye corners (x 21.7 mm),
  // as on an adult: started 11 mm inside them, the two brows nearly met over the
  // nose, so the brows drawn together (anger, sad's AU4) fused into one bar.
  static const Curve2 curve(std::array<vec2, 6>{vec2(0.0170f, 0.0246f), vec2(0.0235f, 0.0280f), vec2(0.0320f, 0.0306f),
                                                 vec2(0.0440f, 0.0304f), vec2(0.0530f, 0.0272f), vec2(0.0585f, 0.0232f)});
  return curve;
}
// Nasolabial fold from beside the nose wing to past the mouth corner.
const Curve2& nasolabialCurve() {
  static const Curve2 curve(std::array<vec2, 5>{vec2(0.0170f, -0.0205f), vec2(0.0240f, -0.0300f),
                                                 vec2(0.0290f, -0.0410f), vec2(0.0315f, -0.0525f),
                                                 vec2(0.0300f, -0.0620f)});
  return curve;
}

const vec3 kSkin = eng::srgb(238, 192, 162);
const vec3 kHair = eng::srgb(66, 44, 32);
const vec3 kBrow = eng::srgb(48, 31, 23);
constexpr float kBrowOpacity = 0.5f;
// A muted rose, half way from a saturated lip red to the skin: a darker, redder
// mouth framed every open mouth in a thick ring that read as a smile.
const vec3 kLip = eng::srgb(191, 125, 110);
const vec3 kLash = eng::srgb(34, 24, 22);

vec4 over(const vec4& under, const vec3& colour, float alpha) {
  // Straight-alpha "over": keeps the strongest coverage and blends colours by it.
  const float a = std::clamp(alpha, 0.0f, 1.0f);
  const float outA = a + under.a * (1.0f - a);
  if (outA <= 0.0f) return vec4(colour, 0.0f);
  return vec4((colour * a + vec3(under) * under.a * (1.0f - a)) / outA, outA);
}

}  // namespace

const std::vector<std::string>& skinDetailLayerNames() {
  static const std::vector<std::string> names = {"forehead_furrows", "brow_knot", "nasolabial_folds", "flush",
                                                 "pallor"};
  return names;
}

float SkinPainter::browHalfWidth(float t) { return 0.0045f - 0.0031f * std::pow(t, 1.4f); }

SkinPainter::SkinPainter(const HeadProportions& proportions, const HeadSdf& sdf) : prop_(proportions), sdf_(sdf) {
  // Brow hairs: roots scattered over the brow body, each growing along the
  // local hair direction (steeply up at the brow head, along the brow after,
  // down toward the tail), with hashed jitter so no two are alike.
  const Curve2& curve = browCurve();
  constexpr int kHairs = 560;
  for (int i = 0; i < kHairs; ++i) {
    const float t = (i + latticeHash(i, 1, 0, 21u)) / kHairs;
    const float across = (latticeHash(i, 2, 0, 21u) * 2.0f - 1.0f) * browHalfWidth(t) * 0.95f;
    const vec2 onCurve = curve.pointAt(t);
    const vec2 tangent = glm::normalize(curve.pointAt(std::min(1.0f, t + 0.01f)) - curve.pointAt(std::max(0.0f, t - 0.01f)));
    const vec2 normal(-tangent.y, tangent.x);
    BrowHair h;
    h.root = onCurve + normal * across - tangent * 0.0012f;
    const float along = std::atan2(tangent.y, tangent.x);
    const float angle = along + (1.05f - 0.95f * glm::smoothstep(0.04f, 0.3f, t)) + (latticeHash(i, 3, 0, 21u) - 0.5f) * 0.35f -
                        0.25f * across / browHalfWidth(t);
    const float length = 0.0030f + 0.0022f * latticeHash(i, 4, 0, 21u);
    h.tip = h.root + vec2(std::cos(angle), std::sin(angle)) * length;
    h.width = 0.00032f + 0.00012f * latticeHash(i, 5, 0, 21u);
    h.darkness = 0.75f + 0.25f * latticeHash(i, 6, 0, 21u);
    h.lo = glm::min(h.root, h.tip) - vec2(h.width);
    h.hi = glm::max(h.root, h.tip) + vec2(h.width);
    browHairs_.push_back(h);
  }
}

float SkinPainter::browCoverage(const vec3& p) const {
  if (p.z < 0.045f) return 0.0f;
  const vec2 q(std::abs(p.x), p.y);
  float t = 0.0f, across = 0.0f;
  if (!browCurve().nearest(q, 0.008f, t, across)) return 0.0f;
  // Soft body of the brow: thick, rounded head; thin, pointed tail.
  const float half = browHalfWidth(t);
  const float body = (1.0f - glm::smoothstep(half * 0.6f, half * (across > 0.0f ? 1.15f : 1.0f), std::abs(across))) *
                     glm::smoothstep(0.0f, 0.08f, t) * (1.0f - glm::smoothstep(0.92f, 1.0f, t));
  // Individual hairs on top of it.
  float hairs = 0.0f;
  for (const BrowHair& h : browHairs_) {
    if (q.x < h.lo.x || q.y < h.lo.y || q.x > h.hi.x || q.y > h.hi.y) continue;
    const vec2 ab = h.tip - h.root;
    const float f = std::clamp(glm::dot(q - h.root, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    const float d = glm::length(q - (h.root + ab * f));
    const float width = h.width * (1.0f - 0.6f * f);  // hairs taper to the tip
    hairs = std::max(hairs, h.darkness * (1.0f - glm::smoothstep(width * 0.5f, width, d)));
  }
  return std::max(0.7f * body, hairs);
}

float SkinPainter::lipCoverage(const vec3& p) const {
  if (p.z < 0.07f || std::abs(p.y - prop_.mouthSeamCentre.y) > 0.016f) return 0.0f;
  // A soft vermilion border (about a millimetre): a hard edge made the lips
  // read as a sticker laid on the face.
  return 1.0f - glm::smoothstep(-0.0009f, 0.0004f, sdf_.lipDistance(p));
}

vec3 SkinPainter::baseColour(const SkinTexel& t) const {
  const vec3& p = t.position;
  const vec2 q(std::abs(p.x), p.y);
  vec3 c = kSkin * (0.965f + 0.07f * fractalNoise(p * 140.0f, 2, 1u));

  // Warmth: cheeks, nose tip, chin; a little cooler under the jaw.
  c = glm::mix(c, eng::srgb(236, 142, 128), 0.24f * gauss2(q - vec2(0.037f, -0.021f), 0.015f) * glm::smoothstep(0.04f, 0.06f, p.z));
  c = glm::mix(c, eng::srgb(232, 148, 132), 0.20f * gauss(glm::length(p - vec3(0.0f, -0.022f, 0.106f)), 0.009f));
  c = glm::mix(c, eng::srgb(232, 158, 140), 0.10f * gauss2(vec2(p.x, p.y + 0.075f), 0.012f) * glm::smoothstep(0.05f, 0.07f, p.z));
  c *= 1.0f - 0.08f * glm::smoothstep(0.2f, 0.9f, -t.normal.y) * glm::smoothstep(-0.06f, -0.09f, p.y);

  // Eyelids: a soft shadow in the upper lid crease, dark lash lines along the edges.
  if (t.eyeSide != 0.0f) {
    const float outer = glm::smoothstep(0.0f, 0.013f, std::abs(p.x) - prop_.eyeCentre.x);
    if (t.upperLid > 0.5f) {
      c = glm::mix(c, eng::srgb(196, 140, 126), 0.22f * glm::smoothstep(0.35f, 0.7f, t.lidRing) * (1.0f - glm::smoothstep(0.88f, 0.95f, t.lidRing)));
      // A lash line thick enough to read at thumbnail size, winged at the outer corner.
      const float lash = glm::smoothstep(0.80f - 0.10f * outer, 0.95f, t.lidRing);
      c = glm::mix(c, kLash, lash);
    } else {
      c = glm::mix(c, eng::srgb(150, 104, 92), 0.55f * glm::smoothstep(0.95f, 0.99f, t.lidRing));
    }
    // Pink inner corner (caruncle).
    const float inner = glm::smoothstep(0.010f, 0.0f, std::abs(p.x) - (prop_.eyeCentre.x - 0.0125f));
    c = glm::mix(c, eng::srgb(214, 128, 122), 0.5f * inner * glm::smoothstep(0.9f, 1.0f, t.lidRing));
  }

  // Brows half over the skin, so they read as hair rather than ink: opaque,
  // they were near-black bars that outweighed the eyes at 256 px, and a dark
  // bar knitted down looked much like a dark bar at rest (over the 12 views of
  // tools/judge_views.py, surprise went from 9 to 12 and anger from 2 to 8).
  c = glm::mix(c, kBrow, kBrowOpacity * browCoverage(p));

  // Lips: darker where they roll in at the seam, a soft sheen on the lower lip.
  const float lip = lipCoverage(p);
  if (lip > 0.0f) {
    const vec3 centre = prop_.gridCentre;
    const vec3 d = p - centre;
    const float elevation = std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z));
    const float seamDistance = std::abs(elevation - sdf_.seamElevation()) * 0.09f;
    vec3 lipColour = glm::mix(kLip * 0.72f, kLip, glm::smoothstep(0.0003f, 0.0022f, seamDistance));
    lipColour = glm::mix(lipColour, eng::srgb(226, 138, 134), 0.22f * gauss2(vec2(p.x, p.y - (prop_.mouthSeamCentre.y - 0.0045f)), 0.005f));
    c = glm::mix(c, lipColour, lip);
  }

  // Nostrils.
  {
    const vec3 m(std::abs(p.x), p.y, p.z);
    const vec3 d = (m - vec3(0.0058f, -0.0312f, 0.0948f)) / vec3(0.0032f, 0.0022f, 0.0042f);
    c = glm::mix(c, eng::srgb(128, 70, 62), 0.45f * std::exp(-glm::dot(d, d)) * glm::smoothstep(0.45f, 0.85f, -t.normal.y));
  }

  // Hair: strands radiating from the crown.
  const float hair = sdf_.hairCoverage(p);
  if (hair > 0.0f) {
    const vec3 fromCrown = p - vec3(0.0f, 0.125f, -0.02f);
    const float around = std::atan2(fromCrown.x, fromCrown.z);
    const float strands = fractalNoise(vec3(around * 90.0f, glm::length(fromCrown) * 160.0f, 3.0f), 2, 5u);
    const vec3 hairColour = kHair * (0.7f + 0.6f * strands);
    c = glm::mix(c, hairColour, hair);
  }

  return c * (0.5f + 0.5f * t.occlusion);
}

vec4 SkinPainter::detail(const std::string& layer, const SkinTexel& t) const {
  const vec3& p = t.position;
  const vec2 q(std::abs(p.x), p.y);
  const bool front = p.z > 0.03f && t.normal.z > 0.0f;
  vec4 out(kSkin, 0.0f);
  const vec3 crease = eng::srgb(150, 96, 80), sheen = eng::srgb(255, 224, 200);
  if (layer == "forehead_furrows") {
    if (!front || p.y < 0.035f) return out;
    for (int k = 0; k < 3; ++k) {
      const float y = 0.0445f + 0.0068f * k + 0.0010f * std::sin(q.x * 150.0f + 1.3f * k) - 0.06f * q.x * q.x;
      const float reach = 0.038f - 0.005f * k;
      const float fade = 1.0f - glm::smoothstep(reach * 0.6f, reach, q.x);
      const float d = p.y - y;
      out = over(out, sheen, 0.30f * fade * gauss(d - 0.0012f, 0.0008f));
      out = over(out, crease, 0.62f * fade * gauss(d, 0.00055f));
    }
    out.a *= 1.0f - sdf_.hairCoverage(p);
    return out;
  }
  if (layer == "brow_knot") {
    if (!front) return out;
    // Two vertical creases between the brows and one across the nose root.
    const float x = q.x - 0.0048f - 0.04f * (p.y - 0.022f) * (p.y - 0.022f) * 30.0f;
    const float vertical = gauss(x, 0.00065f) * glm::smoothstep(0.018f, 0.023f, p.y) * (1.0f - glm::smoothstep(0.033f, 0.038f, p.y));
    const float across = gauss(p.y - 0.0195f, 0.0006f) * (1.0f - glm::smoothstep(0.004f, 0.008f, q.x));
    out = over(out, sheen, 0.25f * gauss(x - 0.0014f, 0.0009f) * glm::smoothstep(0.018f, 0.023f, p.y) *
                               (1.0f - glm::smoothstep(0.033f, 0.038f, p.y)));
    out = over(out, crease, 0.7f * std::max(vertical, across));
    // Shadowed, bunched brow heads.
    out = over(out, eng::srgb(170, 112, 94), 0.3f * gauss2(q - vec2(0.012f, 0.026f), 0.006f));
    return out;
  }
  if (layer == "nasolabial_folds") {
    if (!front) return out;
    float t0 = 0.0f, across = 0.0f;
    if (nasolabialCurve().nearest(q, 0.004f, t0, across)) {
      const float ends = glm::smoothstep(0.0f, 0.12f, t0) * (1.0f - glm::smoothstep(0.75f, 1.0f, t0));
      // Crease, with the bulging cheek highlighted on its outer side.
      out = over(out, sheen, 0.30f * ends * gauss(across + 0.0016f, 0.0011f));
      out = over(out, crease, 0.72f * ends * gauss(across, 0.0007f));
    }
    // Wrinkles across the nose bridge (nose wrinkler).
    for (int k = 0; k < 3; ++k) {
      const float y = 0.0055f + 0.0032f * k - 0.25f * (q.x - 0.006f);
      const float band = gauss(p.y - y, 0.00045f) * glm::smoothstep(0.0015f, 0.004f, q.x) * (1.0f - glm::smoothstep(0.008f, 0.011f, q.x));
      out = over(out, crease, 0.6f * band);
    }
    return out;
  }
  if (layer == "flush") {
    if (!front) return out;
    const float cheeks = gauss2(q - vec2(0.036f, -0.015f), 0.017f);
    const float nose = gauss(glm::length(p - vec3(0.0f, -0.018f, 0.105f)), 0.012f);
    const float forehead = gauss2(vec2(p.x, p.y - 0.045f), 0.03f) * 0.6f;
    const float neck = glm::smoothstep(-0.07f, -0.1f, p.y) * 0.4f;
    const float a = std::min(1.0f, cheeks + 0.8f * nose + forehead + neck);
    return vec4(eng::srgb(206, 70, 62), 0.55f * a * (1.0f - sdf_.hairCoverage(p)) * (1.0f - browCoverage(p)));
  }
  if (layer == "pallor") {
    if (p.z < 0.0f) return out;
    const float face = glm::smoothstep(0.0f, 0.04f, p.z) * (1.0f - sdf_.hairCoverage(p));
    const float lip = lipCoverage(p);
    const float cheeks = gauss2(q - vec2(0.036f, -0.018f), 0.02f);
    // Pale lips keep a lip's hue: whitened lips read as a plastic insert.
    const vec3 colour = glm::mix(eng::srgb(228, 224, 218), eng::srgb(176, 128, 124), lip);
    return vec4(colour, face * (0.42f + 0.2f * cheeks) * (1.0f - browCoverage(p)));
  }
  return out;
}

SkinImages paintSkin(const SkinSurface& s, const std::vector<glm::vec3>& normals, const std::vector<float>& occlusion,
                     const SkinPainter& painter, int baseSize, int detailSize) {
  // Skin triangles only (the mouth pocket has its own material). The parts of
  // the lid patches tucked inside the eyeballs share texture space with the
  // visible lids; they go last so the visible surface claims those texels.
  std::vector<uint32_t> skinTriangles, tucked;
  for (size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    const uint32_t a = s.indices[t], b = s.indices[t + 1], c = s.indices[t + 2];
    if (s.parts[a] != SkinPart::Skin) continue;
    const bool inside = std::max({s.lidRing[a], s.lidRing[b], s.lidRing[c]}) > 1.05f;
    (inside ? tucked : skinTriangles).insert((inside ? tucked : skinTriangles).end(), {a, b, c});
  }
  skinTriangles.insert(skinTriangles.end(), tucked.begin(), tucked.end());
  auto texelAt = [&](uint32_t triangle, const glm::vec3& b) {
    const uint32_t i0 = skinTriangles[triangle * 3], i1 = skinTriangles[triangle * 3 + 1], i2 = skinTriangles[triangle * 3 + 2];
    SkinTexel t;
    t.position = s.positions[i0] * b.x + s.positions[i1] * b.y + s.positions[i2] * b.z;
    t.normal = glm::normalize(normals[i0] * b.x + normals[i1] * b.y + normals[i2] * b.z);
    t.eyeSide = s.eyeSide[i0] != 0.0f ? s.eyeSide[i0] : (s.eyeSide[i1] != 0.0f ? s.eyeSide[i1] : s.eyeSide[i2]);
    t.lidRing = s.lidRing[i0] * b.x + s.lidRing[i1] * b.y + s.lidRing[i2] * b.z;
    t.upperLid = s.upperLid[i0] * b.x + s.upperLid[i1] * b.y + s.upperLid[i2] * b.z;
    t.occlusion = occlusion[i0] * b.x + occlusion[i1] * b.y + occlusion[i2] * b.z;
    return t;
  };
  SkinImages out;
  {
    eng::PaintImage img(baseSize, baseSize);
    eng::rasterizeUv(baseSize, baseSize, s.uvs, skinTriangles, [&](int x, int y, uint32_t tri, const glm::vec3& b) {
      img.set(x, y, vec4(painter.baseColour(texelAt(tri, b)), 1.0f));
    });
    img.dilate(8);
    out.baseColour.name = "skin_base_color";
    out.baseColour.width = out.baseColour.height = baseSize;
    out.baseColour.rgba8 = img.toSrgba8();
  }
  for (const std::string& layer : skinDetailLayerNames()) {
    eng::PaintImage img(detailSize, detailSize);
    eng::rasterizeUv(detailSize, detailSize, s.uvs, skinTriangles, [&](int x, int y, uint32_t tri, const glm::vec3& b) {
      img.set(x, y, painter.detail(layer, texelAt(tri, b)));
    });
    img.dilate(4);
    eng::Image image;
    image.name = "skin_" + layer;
    image.width = image.height = detailSize;
    image.rgba8 = img.toSrgba8();
    out.details.push_back(std::move(image));
  }
  return out;
}

}  // namespace bake
