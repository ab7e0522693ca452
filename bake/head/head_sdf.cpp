#include "bake/head/head_sdf.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>

namespace bake {
namespace {

using glm::vec2;
using glm::vec3;

// Approximate ellipsoid distance (exact on the surface, bounded elsewhere).
float ellipsoid(const vec3& p, const vec3& r) {
  const float k0 = glm::length(p / r);
  const float k1 = glm::length(p / (r * r));
  return k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -std::min({r.x, r.y, r.z});
}

// Polynomial smooth minimum: blends two shapes with a fillet of size ~k.
float smin(float a, float b, float k) {
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}
float smax(float a, float b, float k) { return -smin(-a, -b, k); }

float dot2(const vec3& v) { return glm::dot(v, v); }

// Cone with rounded ends of radii r1 at a and r2 at b.
float roundCone(const vec3& p, const vec3& a, const vec3& b, float r1, float r2) {
  const vec3 ba = b - a;
  const float l2 = glm::dot(ba, ba);
  const float rr = r1 - r2;
  const float a2 = l2 - rr * rr;
  const float il2 = 1.0f / l2;
  const vec3 pa = p - a;
  const float y = glm::dot(pa, ba);
  const float z = y - l2;
  const float x2 = dot2(pa * l2 - ba * y);
  const float y2 = y * y * l2;
  const float z2 = z * z * l2;
  const float k = (rr > 0 ? 1.0f : -1.0f) * rr * rr * x2;
  if ((z > 0 ? 1.0f : -1.0f) * a2 * z2 > k) return std::sqrt(x2 + z2) * il2 - r2;
  if ((y > 0 ? 1.0f : -1.0f) * a2 * y2 < k) return std::sqrt(x2 + y2) * il2 - r1;
  return (std::sqrt(x2 * a2 * il2) + y * rr) * il2 - r1;
}

// Piecewise smooth interpolation through (x, y) keys sorted by x.
template <size_t N>
float smoothKeys(const std::array<vec2, N>& keys, float x) {
  if (x <= keys.front().x) return keys.front().y;
  for (size_t i = 1; i < N; ++i)
    if (x <= keys[i].x) {
      const float t = glm::smoothstep(keys[i - 1].x, keys[i].x, x);
      return keys[i - 1].y + (keys[i].y - keys[i - 1].y) * t;
    }
  return keys.back().y;
}

float elevationFrom(const vec3& centre, const vec3& p) {
  const vec3 d = p - centre;
  return std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z));
}

}  // namespace

HeadSdf::HeadSdf(const HeadProportions& proportions) : prop_(proportions) {
  seamElevation_ = elevationFrom(prop_.gridCentre, prop_.mouthSeamCentre);
  // Walk along the seam cone until the skin reaches the mouth half-width.
  seamGroove_ = false;
  const float ce = std::cos(seamElevation_), se = std::sin(seamElevation_);
  for (float azimuth = 0.0f; azimuth < 0.8f; azimuth += 0.0005f) {
    const vec3 dir(ce * std::sin(azimuth), se, ce * std::cos(azimuth));
    const std::optional<vec3> hit = castOut(prop_.gridCentre, dir);
    if (hit && hit->x >= prop_.mouthHalfWidth) {
      cornerAzimuth_ = azimuth;
      break;
    }
  }
  seamGroove_ = true;
}

float HeadSdf::face(const vec3& p) const {
  // Cranium.
  float d = ellipsoid(p - vec3(0.0f, 0.032f, -0.010f), vec3(0.0765f, 0.092f, 0.098f));
  // Lower face: one volume from the cheekbones to the jaw, narrowing toward
  // the chin (a stylised V jaw). One shape rather than a mid-face and a
  // mandible blended together: their junction left a groove across the cheek.
  // Adult proportions: pupils to chin about 0.8 of the cheek width (a shorter
  // lower face read as a child's, a wider one as a mask), and a gentle taper:
  // a sharper V turned the cheeks below the eyes sideways, away from the key
  // light, so the far cheek fell into a hard-edged dark band.
  {
    const float narrow = 1.0f - 0.14f * glm::smoothstep(-0.020f, -0.093f, p.y) * glm::smoothstep(-0.03f, 0.07f, p.z);
    vec3 f = p - vec3(0.0f, -0.036f, 0.028f);
    f.x /= narrow;
    float lower = ellipsoid(f, vec3(0.061f, 0.064f, 0.061f)) * narrow;
    // The jaw's underside: a plane rising from under the chin to the jaw
    // angles. Without it the ellipsoid's round bottom hung below the jaw like
    // a balloon and the jaw line never formed.
    const vec3 underChin(0.0f, -0.089f, 0.066f);
    const vec3 down = glm::normalize(vec3(0.0f, -0.89f, -0.45f));
    lower = smax(lower, glm::dot(p - underChin, down), 0.012f);
    d = smin(d, lower, 0.03f);
  }
  // Chin, forward under the lower lip (a chin set back behind the lips gave a
  // receding, doll-like profile), and the muzzle over the teeth, wide and
  // blended wide so the cheeks flow into it: a narrow muzzle left a groove
  // from the nose wing down to the jaw, a hard dark band under the key light
  // and a smile's fold on a face at rest.
  d = smin(d, ellipsoid(p - vec3(0.0f, -0.083f, 0.0735f), vec3(0.0195f, 0.0140f, 0.0170f)), 0.018f);
  d = smin(d, ellipsoid(p - vec3(0.0f, -0.047f, 0.060f), vec3(0.038f, 0.024f, 0.026f)), 0.032f);
  // Brow ridge, a low one. Measured against a scanned face (facecap, scaled
  // to the same eye spacing) the head's upper lids sat 5-9 mm deeper under
  // the brow: under the key light a dark ledge that merged with the brows
  // into one heavy arc, and raised brows (sad's AU1) stretched it into a dark
  // patch over the inner socket. 6 mm further back than it was.
  d = smin(d, ellipsoid(p - vec3(0.0f, 0.029f, 0.062f), vec3(0.056f, 0.013f, 0.024f)), 0.02f);
  // Cheekbones and cheek apples (mirrored), blended wide so they shape the
  // face without reading as separate lumps.
  const vec3 m(std::abs(p.x), p.y, p.z);
  d = smin(d, ellipsoid(m - vec3(0.046f, -0.004f, 0.036f), vec3(0.016f, 0.014f, 0.030f)), 0.034f);
  d = smin(d, ellipsoid(m - vec3(0.035f, -0.015f, 0.060f), vec3(0.019f, 0.016f, 0.017f) * 0.85f), 0.028f);
  // Neck: a cylinder merged under the skull, cut flat at the bottom. An
  // adult's, about as wide as the jaw and long enough to leave the portrait
  // framing: a thin stub cut off just under the chin read as a child's neck
  // on a plinth.
  {
    // A tighter blend under the jaw than around the skull: a readable jaw line.
    const vec2 q(p.x / 0.046f, (p.z + 0.024f) / 0.046f);
    const float neck = std::max((glm::length(q) - 1.0f) * 0.046f, p.y);
    d = smin(d, neck, 0.02f + 0.01f * glm::smoothstep(0.0f, -0.04f, p.z));
    d = smax(d, prop_.neckBottomY - p.y, 0.012f);
  }
  return d;
}

float HeadSdf::nose(const vec3& p) const {
  float n = roundCone(p, vec3(0.0f, 0.018f, 0.0770f), vec3(0.0f, -0.017f, 0.0985f), 0.0060f, 0.0068f);
  n = smin(n, glm::length(p - vec3(0.0f, -0.0215f, 0.0995f)) - 0.0084f, 0.008f);
  const vec3 m(std::abs(p.x), p.y, p.z);
  n = smin(n, ellipsoid(m - vec3(0.0115f, -0.0265f, 0.0900f), vec3(0.0065f, 0.0060f, 0.0070f)), 0.005f);
  // Nostrils: shallow dents under the tip.
  n = smax(n, -ellipsoid(m - vec3(0.0058f, -0.0310f, 0.0948f), vec3(0.0030f, 0.0020f, 0.0042f)), 0.0015f);
  return n;
}

// The lips are not separate shapes laid on the face: they are the muzzle's
// own surface raised inside the vermilion outline. Within the outline the
// raise grows from the seam (where the lips roll in) to a full lip and rolls
// off gradually toward the vermilion border, the lower lip on into the skin
// under it: a crisp ridge there drew a dark outline round each lip at 256 px,
// which with the seam read as a mouth held open (a sad mouth taken for a
// fearful one). Toward the corners the raise fades to nothing, so the
// corners tuck into the face.
HeadSdf::LipBand HeadSdf::lipBand(float ax) const {
  const float w = prop_.mouthHalfWidth + 0.0006f;
  const float f = std::min(ax / w, 1.0f);
  const float across = std::max(0.0f, 1.0f - f * f);
  LipBand b;
  // Cupid's bow: two peaks either side of the philtrum, a dip on the midline.
  const float bow = 0.0009f * std::exp(-std::pow((ax - 0.0047f) / 0.0026f, 2.0f)) -
                    0.0005f * std::exp(-std::pow(ax / 0.0020f, 2.0f));
  b.upperHeight = 0.0056f * std::pow(across, 0.55f) + bow * across;
  b.lowerHeight = 0.0074f * std::pow(across, 0.6f);
  b.upperRaise = 0.0022f * std::pow(across, 0.8f);
  b.lowerRaise = 0.0032f * std::pow(across, 0.8f);
  b.seamRaise = 0.0011f * std::pow(across, 0.8f);
  return b;
}

float HeadSdf::seamHeight(const vec3& p) const {
  // Height of the seam cone above/below p: the lips are measured from the
  // seam the mesh is split along, wherever the skin around it lies.
  const vec3 d = p - prop_.gridCentre;
  return prop_.gridCentre.y + std::tan(seamElevation_) * std::sqrt(d.x * d.x + d.z * d.z);
}

float HeadSdf::lipRaise(const vec3& p) const {
  if (p.z < 0.06f) return 0.0f;
  const LipBand b = lipBand(std::abs(p.x));
  const float dy = p.y - seamHeight(p);
  if (dy >= 0.0f) {
    if (b.upperHeight <= 0.0f) return 0.0f;
    const float u = dy / b.upperHeight;
    return (b.seamRaise + (b.upperRaise - b.seamRaise) * glm::smoothstep(0.0f, 0.55f, u)) * (1.0f - glm::smoothstep(0.30f, 1.0f, u));
  }
  if (b.lowerHeight <= 0.0f) return 0.0f;
  const float u = -dy / b.lowerHeight;
  return (b.seamRaise + (b.lowerRaise - b.seamRaise) * glm::smoothstep(0.0f, 0.5f, u)) * (1.0f - glm::smoothstep(0.10f, 1.40f, u));
}

float HeadSdf::lipDistance(const vec3& p) const {
  // Front-projected distance to the vermilion outline (negative inside).
  const float ax = std::abs(p.x);
  const LipBand b = lipBand(ax);
  const float dy = p.y - seamHeight(p);
  const float outside = dy >= 0.0f ? dy - b.upperHeight : -dy - b.lowerHeight;
  return std::max(outside, ax - (prop_.mouthHalfWidth + 0.0006f));
}

float HeadSdf::eyeRegion(float d, const vec3& p) const {
  for (float side : {1.0f, -1.0f}) {
    const vec3 e(prop_.eyeCentre.x * side, prop_.eyeCentre.y, prop_.eyeCentre.z);
    // Beyond the socket's reach (dish radius + blend, lid shell + blend) nothing changes.
    if (glm::length(p - e) > prop_.eyeRadius * 3.2f + 0.016f) continue;
    // Socket: a shallow dish in the face in front of the eye; the eyeball's
    // lid shell rises out of it. Both are star-shaped around the eye, so rays
    // from behind the eyeball cross the skin once.
    const float r = prop_.eyeRadius;
    // The dish stops short of the nose bridge (a dish reaching the midline
    // leaves a thin ridge there with a dark crease along each side). It is
    // shallow and centred a little below the eye, so the upper lid is full
    // under the brow as on a scanned face: a deep dish under the brow ridge
    // left deep-set eyes in a dark band under the key light.
    d = smax(d, -ellipsoid(p - (e + vec3(0.18f * side, -0.1f, 2.0f) * r), vec3(1.42f, 1.25f, 0.95f) * r), 0.016f);
    const float thickness = prop_.lowerLidThickness + (prop_.upperLidThickness - prop_.lowerLidThickness) *
                                                         glm::smoothstep(-0.004f, 0.004f, p.y - e.y);
    d = smin(d, glm::length(p - e) - (prop_.eyeRadius + thickness), 0.0075f);
  }
  return d;
}

namespace {

// Hairline height around the head: forehead, temples, sideburns, nape.
float hairlineHeight(const vec3& p) {
  static constexpr std::array<vec2, 7> kHairline = {vec2(0.00f, 0.070f), vec2(0.35f, 0.071f), vec2(0.62f, 0.062f),
                                                    vec2(1.10f, 0.042f), vec2(1.45f, 0.022f), vec2(2.20f, -0.015f),
                                                    vec2(3.15f, -0.045f)};
  return smoothKeys(kHairline, std::abs(std::atan2(p.x, p.z)));
}

}  // namespace

float HeadSdf::hairCoverage(const vec3& p) const {
  const float h = hairlineHeight(p);
  return glm::smoothstep(h - 0.0025f, h + 0.0025f, p.y);
}

float HeadSdf::hairVolume(const vec3& p) const {
  const float h = hairlineHeight(p);
  return glm::smoothstep(h - 0.002f, h + 0.009f, p.y);
}

float HeadSdf::distance(const vec3& p) const {
  // Features are only evaluated near their bounding spheres: smin(a, b, k)
  // equals a whenever b >= a + k, and rays and relaxation evaluate this
  // function millions of times.
  float d = face(p);
  if (glm::length(p - vec3(0.0f, -0.004f, 0.091f)) - 0.034f < d + 0.011f) d = smin(d, nose(p), 0.011f);
  if (std::abs(p.y - prop_.mouthSeamCentre.y) < 0.012f && std::abs(p.x) < 0.026f) d -= lipRaise(p);
  d = eyeRegion(d, p);
  // The lip seam: a sharp groove along the seam cone between the mouth corners.
  if (seamGroove_ && std::abs(p.y - prop_.mouthSeamCentre.y) < 0.02f && p.z > 0.04f) {
    const vec3 c = prop_.gridCentre;
    const float elevation = elevationFrom(c, p);
    const float around = std::atan2(p.x - c.x, p.z - c.z);
    const float span = 1.0f - glm::smoothstep(cornerAzimuth_ - 0.035f, cornerAzimuth_ + 0.006f, std::abs(around));
    const float u = (elevation - seamElevation_) / 0.0075f;
    d += 0.0012f * std::exp(-u * u) * span;
  }
  // Hair volume over the scalp, fuller on top.
  const float hair = p.y > -0.06f ? hairVolume(p) : 0.0f;
  if (hair > 0.0f) d -= hair * (0.003f + 0.004f * glm::smoothstep(0.03f, 0.11f, p.y));
  return d;
}

float HeadSdf::occlusion(const vec3& p, const vec3& n) const {
  // Classic distance-field AO: how much closer the surface is than the
  // sample distance along the normal, weighted toward near samples.
  float blocked = 0.0f, weight = 1.0f;
  for (int i = 1; i <= 5; ++i) {
    const float h = 0.0022f * float(i);
    blocked += weight * std::max(0.0f, h - distance(p + n * h)) / h;
    weight *= 0.6f;
  }
  return std::clamp(1.0f - 0.75f * blocked, 0.0f, 1.0f);
}

glm::vec3 HeadSdf::normal(const vec3& p) const {
  const float h = 1e-4f;
  const vec3 g(distance(p + vec3(h, 0, 0)) - distance(p - vec3(h, 0, 0)),
               distance(p + vec3(0, h, 0)) - distance(p - vec3(0, h, 0)),
               distance(p + vec3(0, 0, h)) - distance(p - vec3(0, 0, h)));
  const float len = glm::length(g);
  return len > 0.0f ? g / len : vec3(0, 0, 1);
}

std::optional<glm::vec3> HeadSdf::castOut(const vec3& origin, const vec3& dir, float maxT) const {
  float prevT = 0.0f;
  float d = distance(origin);
  if (d >= 0.0f) return std::nullopt;
  float t = 0.0f;
  while (t < maxT) {
    prevT = t;
    // Long strides deep inside, short ones near the skin so thin features
    // (lids, lips) are not stepped over.
    t += std::clamp(std::abs(d) * 0.6f, 1.5e-4f, std::abs(d) > 0.012f ? 6e-3f : 2.5e-3f);
    d = distance(origin + dir * t);
    if (d >= 0.0f) {
      float lo = prevT, hi = t;
      for (int i = 0; i < 40; ++i) {
        const float mid = 0.5f * (lo + hi);
        (distance(origin + dir * mid) < 0.0f ? lo : hi) = mid;
      }
      return origin + dir * (0.5f * (lo + hi));
    }
  }
  return std::nullopt;
}

}  // namespace bake
