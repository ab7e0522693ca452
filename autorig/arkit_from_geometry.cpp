#include "autorig/arkit_from_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

#include "facial/runtime/character/gaze_rig.h"

namespace autorig {
namespace {

// Largest travel at full weight, in eye spans: facecap's own shapes (jawLeft
// 0.10, mouthLeft 0.14, cheekPuff 0.11, mouthDimple 0.115 of its outer eye
// corners' distance).
constexpr float kJawSideways = 0.10f;
// jawForward: the jaw slid forward, as the mandible's condyles glide down
// their slope: facecap's travels 1.04 times its jawLeft, dropping 0.083 of
// its travel (the whole jaw alike, where the head's AU29 pushes the chin).
constexpr float kJawForward = 0.104f;
constexpr float kJawForwardDrop = 0.083f;
constexpr float kMouthSideways = 0.14f;
constexpr float kCheekPuff = 0.11f;
constexpr float kPuffOut = 0.15f;     // of the way from a lip corner to the jaw line
constexpr float kPuffRadius = 0.6f;  // eye spans
constexpr float kDimple = 0.115f;
// mouthShrugUpper: facecap's upper lip rises 0.055 eye spans as one piece,
// rim to top (the lower lip pushing it), the skin above it less toward the
// nose's base and its corners little (0.007).
constexpr float kShrugUpper = 0.055f;
// mouthLowerDown: facecap's lower lip drawn down 0.085 eye spans beside the
// middle, and back 0.2 of that, less toward the chin and the corners.
constexpr float kLowerLipDown = 0.085f;
constexpr float kLowerLipBack = 0.2f;
// mouthClose over jawOpen: facecap's lower lip goes back 0.65 of its opening
// and its upper lip comes down 0.37 of it, so they meet.
constexpr float kLowerLipReturn = 0.65f;
constexpr float kUpperLipDrop = 0.37f;
// The share of its eye's turn the lid line follows (a lid rides on the
// cornea: facecap's lids move 0.04-0.05 eye spans at a full look), fading
// out between 0.4 and 0.8 of the eye's width from the eye's middle, so the
// brows stay.
constexpr float kLidFollow = 0.45f;
constexpr float kLidNear = 0.15f, kLidFar = 0.6f;
constexpr float kLowerLidUp = 0.1f, kLowerLidDown = 0.6f;
// The outer skin: cells of the face's plane (eye spans) and how far behind
// the front-most skin about a vertex it starts and stops being outside.
constexpr float kOuterCell = 0.03f;
constexpr float kOuterNear = 0.04f, kOuterFar = 0.1f;
// Skin farther behind the face's landmark plane than this (eye spans) is the
// side or back of the head.
constexpr float kFrontDepth = -0.5f;

float fade(float edge0, float edge1, float x) { return 1.0f - glm::smoothstep(edge0, edge1, x); }

bool isSkin(FacePart part) { return part == FacePart::Skin || part == FacePart::Lashes; }

class Maker {
 public:
  Maker(std::span<const NamedDeltas> units, const ShapeGeometry& g)
      : g_(g), l_(g.landmarks->points), f_(*g.frame), span_(g.frame->eyeSpan()), units_(units), outer_(outerSkin()) {}

  // Nullopt when the face lacks what the shape is made from.
  std::optional<std::vector<glm::vec3>> make(std::string_view name) const {
    struct Look {
      std::string_view name;
      int eye;  // 0: the subject's right, 1: left
      glm::vec3 toward;
    };
    const glm::vec3 side = f_.side(), up = f_.up();
    // Out is away from the nose: the left eye's out is +side, the right's -side.
    const Look looks[] = {{"eyeLookDownLeft", 1, -up},  {"eyeLookInLeft", 1, -side}, {"eyeLookOutLeft", 1, side},
                          {"eyeLookUpLeft", 1, up},     {"eyeLookDownRight", 0, -up}, {"eyeLookInRight", 0, side},
                          {"eyeLookOutRight", 0, -side}, {"eyeLookUpRight", 0, up}};
    for (const Look& look : looks)
      if (name == look.name) return gaze(look.eye, look.toward);
    if (name == "jawLeft") return jawSideways(1.0f);
    if (name == "jawRight") return jawSideways(-1.0f);
    if (name == "jawForward") return jawShifted(kJawForward * glm::normalize(f_.forward() - kJawForwardDrop * f_.up()));
    if (name == "mouthLeft") return mouthSideways(1.0f);
    if (name == "mouthRight") return mouthSideways(-1.0f);
    if (name == "mouthClose") return mouthClose();
    if (name == "mouthShrugUpper") return shrugUpper();
    if (name == "mouthLowerDownLeft") return lowerLipDown(true);
    if (name == "mouthLowerDownRight") return lowerLipDown(false);
    if (name == "cheekPuff") return cheekPuff();
    if (name == "mouthDimpleLeft") return dimple(1.0f);
    if (name == "mouthDimpleRight") return dimple(-1.0f);
    return std::nullopt;
  }

 private:
  size_t count() const { return g_.positions.size(); }
  float depth(const glm::vec3& p) const { return glm::dot(p - f_.origin(), f_.forward()) / span_; }

  // Not the side or back of the head, which projects onto the same places
  // of the face's plane.
  float inFront(const glm::vec3& p) const { return glm::smoothstep(kFrontDepth - 0.2f, kFrontDepth, depth(p)); }

  // How much each skin vertex is the face's outside seen from the front: 1
  // near the front-most skin about it, 0 well behind it (the inside of the
  // mouth behind the lips, the back of the head), which the mouth and cheek
  // shapes leave alone as a real capture does.
  std::vector<float> outerSkin() const {
    auto cellOf = [&](const glm::vec3& p) {
      const glm::vec3 q = p - f_.origin();
      // Clamped: a stray vertex far off (a hostile file) must not overflow the cast.
      const glm::vec2 cell = glm::vec2(glm::dot(q, f_.side()), glm::dot(q, f_.up())) / (kOuterCell * span_);
      if (!std::isfinite(cell.x) || !std::isfinite(cell.y)) return glm::ivec2(2000000);  // a cell of its own
      return glm::ivec2(glm::clamp(glm::floor(cell), glm::vec2(-1e6f), glm::vec2(1e6f)));
    };
    auto key = [](glm::ivec2 c) { return (int64_t(c.x) << 32) ^ int64_t(uint32_t(c.y)); };
    std::unordered_map<int64_t, float> frontMost;
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      auto [it, added] = frontMost.try_emplace(key(cellOf(g_.positions[v])), depth(g_.positions[v]));
      if (!added) it->second = std::max(it->second, depth(g_.positions[v]));
    }
    std::vector<float> outer(count(), 0.0f);
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::ivec2 c = cellOf(g_.positions[v]);
      float ahead = depth(g_.positions[v]);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (auto it = frontMost.find(key(c + glm::ivec2(dx, dy))); it != frontMost.end()) ahead = std::max(ahead, it->second);
      outer[v] = fade(kOuterNear, kOuterFar, ahead - depth(g_.positions[v]));
    }
    return outer;
  }
  float mouthHalfWidth() const { return 0.5f * std::abs(f_.sideOf(l_[54]) - f_.sideOf(l_[48])); }
  float mouthMiddle() const { return 0.5f * (f_.sideOf(l_[54]) + f_.sideOf(l_[48])); }

  // Each eyeball turned about its centre toward `toward`; the skin around it
  // by a share that is kLidFollow at the lid line (the turn scaled, so a lid
  // stays on the ball's sphere).
  std::optional<std::vector<glm::vec3>> gaze(int eye, const glm::vec3& toward) const {
    const FaceParts& parts = *g_.faceParts;
    if (!parts.eyeballsFound || !(parts.eyeRadii[eye] > 0.0f) || parts.eyesInTheSkin[size_t(eye)]) return std::nullopt;
    const glm::vec3 centre = parts.eyeCentres[eye];
    const float radius = parts.eyeRadii[eye];
    const FacePart ball = eye == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
    const int first = eye == 0 ? 36 : 42;
    glm::vec3 middle(0.0f);
    for (int k = 0; k < 6; ++k) middle += l_[size_t(first + k)];
    middle /= 6.0f;
    const float width = glm::distance(l_[size_t(first)], l_[size_t(first + 3)]);
    const glm::vec3 axis = glm::normalize(glm::cross(f_.forward(), toward));
    // facecap's lower lid stays when the eye looks up and follows it down
    // at 0.6 of the upper lid's travel; both lids go with a look aside.
    const float vertical = glm::dot(toward, f_.up());
    const float lowerLid = vertical > 0.5f ? kLowerLidUp : vertical < -0.5f ? kLowerLidDown : 1.0f;
    const float full = glm::radians(facial::kArkitLookDegrees);
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    bool any = false;
    for (size_t v = 0; v < count(); ++v) {
      const glm::vec3& p = g_.positions[v];
      float share = 0.0f;
      if (g_.parts[v] == ball) {
        share = 1.0f;
      } else if (isSkin(g_.parts[v])) {
        const glm::vec3 q = p - middle;
        const float across = glm::length(glm::vec2(glm::dot(q, f_.side()), glm::dot(q, f_.up())));
        const float before = glm::smoothstep(-0.2f * radius, 0.2f * radius, glm::dot(p - centre, f_.forward()));
        // The lower lid: how much of the upper lid's share it has, blended across the lid line.
        const float upper = glm::smoothstep(-0.1f * width, 0.1f * width, glm::dot(q, f_.up()));
        share = kLidFollow * fade(kLidNear * width, kLidFar * width, across) * before * glm::mix(lowerLid, 1.0f, upper);
      }
      if (!(share > 0.0f)) continue;
      const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), share * full, axis));
      deltas[v] = turn * (p - centre) - (p - centre);
      any = true;
    }
    if (!any) return std::nullopt;
    return deltas;
  }

  // How much of the jaw's motion each vertex has: its travel in the made jaw
  // drop over the chin's (the skin nearest landmark 8), at most 1.
  std::optional<std::vector<float>> jawShare() const {
    const NamedDeltas* drop = findUnit(units_, "AU26_JawDrop", count());
    if (!drop) return std::nullopt;
    const std::optional<size_t> chin = nearestSkin(l_[8]);
    if (!chin) return std::nullopt;
    const float chinTravel = glm::length(drop->deltas[*chin]);
    if (!(chinTravel > 1e-4f * span_)) return std::nullopt;
    std::vector<float> share(count());
    for (size_t v = 0; v < count(); ++v) share[v] = std::min(glm::length(drop->deltas[v]) / chinTravel, 1.0f);
    return share;
  }

  std::optional<std::vector<glm::vec3>> jawSideways(float sign) const { return jawShifted(sign * kJawSideways * f_.side()); }

  // Each vertex moved by its share of the jaw's motion times `atTheChin` (in eye spans).
  std::optional<std::vector<glm::vec3>> jawShifted(const glm::vec3& atTheChin) const {
    const std::optional<std::vector<float>> share = jawShare();
    if (!share) return std::nullopt;
    std::vector<glm::vec3> deltas(count());
    for (size_t v = 0; v < count(); ++v) deltas[v] = span_ * (*share)[v] * atTheChin;
    return deltas;
  }

  // `direction` turned into the skin's tangent plane at v, its length kept:
  // what slides over the face goes back where the face curves away.
  glm::vec3 alongSurface(size_t v, const glm::vec3& direction) const {
    if (v >= g_.normals.size()) return direction;
    const glm::vec3& n = g_.normals[v];
    const glm::vec3 tangent = direction - glm::dot(direction, n) * n;
    const float length = glm::length(tangent);
    return length > 1e-3f ? tangent / length : direction;
  }

  // The lips and the skin about them, fading out by the nose's base, the
  // chin and a little beyond the corners; teeth and tongue stay.
  std::optional<std::vector<glm::vec3>> mouthSideways(float sign) const {
    const float halfWidth = mouthHalfWidth(), middle = mouthMiddle();
    const float toNose = f_.aboveLipLine(l_[33]), toChin = -f_.aboveLipLine(l_[8]);
    if (!(halfWidth > 0.0f) || !(toNose > 0.0f) || !(toChin > 0.0f)) return std::nullopt;
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      const float above = f_.aboveLipLine(p);
      const float u = (f_.sideOf(p) - middle) / (1.6f * halfWidth);
      const float h = above > 0.0f ? above / toNose : -above / toChin;
      const float w = fade(0.55f, 1.0f, std::sqrt(u * u + h * h)) * inFront(p);
      deltas[v] = sign * kMouthSideways * span_ * w * alongSurface(v, f_.side());
    }
    return deltas;
  }

  // The upper lip pushed straight up: in full from its inner rim to its top
  // (a quarter of the way to the nose's base), fading out by the nose's base
  // and at the corners. Which lip a vertex is by how far the jaw takes it
  // (the lower lip goes with the jaw); the inside of the mouth stays.
  std::optional<std::vector<glm::vec3>> shrugUpper() const {
    const std::optional<std::vector<float>> share = jawShare();
    const float halfWidth = mouthHalfWidth(), middle = mouthMiddle();
    const float toNose = f_.aboveLipLine(l_[33]);
    if (!share || !(halfWidth > 0.0f) || !(toNose > 0.0f)) return std::nullopt;
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      const float upperLip = 1.0f - glm::smoothstep(0.2f, 0.5f, (*share)[v]);
      const float towardNose = fade(0.25f, 1.0f, std::max(f_.aboveLipLine(p), 0.0f) / toNose);
      const float across = fade(0.5f, 1.1f, std::abs(f_.sideOf(p) - middle) / halfWidth);
      deltas[v] = kShrugUpper * span_ * upperLip * towardNose * across * outer_[v] * inFront(p) * f_.up();
    }
    return deltas;
  }

  // One half of the lower lip drawn down and back, in full beside the
  // middle, fading out toward the chin and past the corner (a half of the
  // whole, as the units' halves are); the lower lip is what the jaw takes,
  // the inside of the mouth and the teeth stay.
  std::optional<std::vector<glm::vec3>> lowerLipDown(bool left) const {
    const std::optional<std::vector<float>> share = jawShare();
    const float halfWidth = mouthHalfWidth(), middle = mouthMiddle();
    const float toChin = -f_.aboveLipLine(l_[8]);
    if (!share || !(halfWidth > 0.0f) || !(toChin > 0.0f)) return std::nullopt;
    const glm::vec3 direction = glm::normalize(-f_.up() - kLowerLipBack * f_.forward());
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      const float lowerLip = glm::smoothstep(0.2f, 0.5f, (*share)[v]);
      const float towardChin = fade(0.0f, 1.0f, std::max(-f_.aboveLipLine(p), 0.0f) / toChin);
      const float across = fade(0.6f, 1.1f, std::abs(f_.sideOf(p) - middle) / halfWidth);
      const float half = left ? leftHalf(p, f_) : 1.0f - leftHalf(p, f_);
      deltas[v] = kLowerLipDown * span_ * lowerLip * towardChin * across * half * outer_[v] * inFront(p) * direction;
    }
    return deltas;
  }

  // ARKit's mouthClose is driven with jawOpen: the lips together while the
  // jaw stays open. The lower lip goes back up by kLowerLipReturn of the
  // made jaw opening (AU26 + AU27, as jawOpen) there, less toward the chin;
  // the upper lip comes down by kUpperLipDrop of the lower lip's opening
  // beneath it (so they meet at the corners too), less toward the nose. The
  // inside of the mouth goes with them (facecap's stays): held back, the
  // lips' inner rims tear from them.
  std::optional<std::vector<glm::vec3>> mouthClose() const {
    const NamedDeltas* drop = findUnit(units_, "AU26_JawDrop", count());
    if (!drop) return std::nullopt;
    const NamedDeltas* stretch = findUnit(units_, "AU27_MouthStretch", count());
    auto opening = [&](size_t v) { return stretch ? drop->deltas[v] + stretch->deltas[v] : drop->deltas[v]; };
    const float halfWidth = mouthHalfWidth(), middle = mouthMiddle();
    const float toNose = f_.aboveLipLine(l_[33]), toChin = -f_.aboveLipLine(l_[8]);
    const float lowerLip = -f_.aboveLipLine(l_[57]);
    if (!(halfWidth > 0.0f) || !(toNose > 0.0f) || !(toChin > lowerLip) || !(lowerLip > 0.0f)) return std::nullopt;

    // The lower lip's opening along the mouth, in kBins across 1.5 half-widths each side.
    constexpr int kBins = 32;
    const float from = middle - 1.5f * halfWidth, binWidth = 3.0f * halfWidth / kBins;
    std::array<glm::vec3, kBins> sum{};
    std::array<float, kBins> weight{};
    for (size_t v = 0; v < count(); ++v) {
      const float below = -f_.aboveLipLine(g_.positions[v]);
      if (!isSkin(g_.parts[v]) || below < 0.0f || below > lowerLip || !(outer_[v] > 0.5f)) continue;
      const float at = (f_.sideOf(g_.positions[v]) - from) / binWidth;
      if (!(at >= 0.0f && at < float(kBins))) continue;
      const int bin = int(at);
      sum[size_t(bin)] += opening(v), weight[size_t(bin)] += 1.0f;
    }
    std::array<glm::vec3, kBins> lowerOpening{};
    for (int b = 0; b < kBins; ++b)  // an empty bin takes its nearest filled one's
      for (int d = 0; d < kBins; ++d) {
        const int before = b - d, after = b + d;
        const int filled = before >= 0 && weight[size_t(before)] > 0.0f ? before
                           : after < kBins && weight[size_t(after)] > 0.0f ? after
                                                                          : -1;
        if (filled < 0) continue;
        lowerOpening[size_t(b)] = sum[size_t(filled)] / weight[size_t(filled)];
        break;
      }
    auto openingBeneath = [&](float x) {
      const float t = glm::clamp((x - from) / binWidth - 0.5f, 0.0f, float(kBins - 1));
      const int b = std::min(int(t), kBins - 2);
      return glm::mix(lowerOpening[size_t(b)], lowerOpening[size_t(b + 1)], t - float(b));
    };

    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      const float above = f_.aboveLipLine(p);
      const float across = fade(1.0f, 1.5f, std::abs(f_.sideOf(p) - middle) / halfWidth) * inFront(p);
      // Which lip a vertex is by how far the jaw takes it, not by the
      // landmarks' line, which the mesh's lip edge zig-zags about.
      const glm::vec3 beneath = openingBeneath(f_.sideOf(p));
      const float lower = glm::smoothstep(0.3f, 0.7f, glm::length(opening(v)) / std::max(glm::length(beneath), 1e-6f * span_));
      const float towardNose = above > 0.0f ? fade(0.3f, 1.0f, above / toNose) : 1.0f;
      const float towardChin = above < 0.0f ? fade(0.15f, 1.0f, -above / toChin) : 1.0f;
      deltas[v] = across * (lower * -kLowerLipReturn * towardChin * opening(v) +
                            (1.0f - lower) * kUpperLipDrop * towardNose * beneath);
    }
    return deltas;
  }

  std::optional<size_t> nearestSkin(const glm::vec3& point) const {
    std::optional<size_t> nearest;
    float best = std::numeric_limits<float>::infinity();
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const float d = glm::distance(g_.positions[v], point);
      if (d < best) best = d, nearest = v;
    }
    return nearest;
  }

  // The cheeks beside the lip corners pushed forward (facecap's puff moves
  // the skin just out from the corners most, and forward).
  std::optional<std::vector<glm::vec3>> cheekPuff() const {
    const glm::vec3 centres[2] = {glm::mix(l_[48], l_[4], kPuffOut), glm::mix(l_[54], l_[12], kPuffOut)};
    const float radius = kPuffRadius * span_;
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    bool any = false;
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      float w = 0.0f;
      for (const glm::vec3& centre : centres) w = std::max(w, fade(0.0f, radius, glm::distance(p, centre)));
      w *= outer_[v];
      if (w > 0.0f) deltas[v] = kCheekPuff * span_ * w * f_.forward(), any = true;
    }
    if (!any) return std::nullopt;
    return deltas;
  }

  // The lip corner drawn back into the cheek, out and a little up (facecap's
  // dimple: back 0.79, out 0.47, up 0.39).
  std::optional<std::vector<glm::vec3>> dimple(float sign) const {
    const glm::vec3& corner = sign > 0.0f ? l_[54] : l_[48];
    const float halfWidth = mouthHalfWidth() * span_;
    if (!(halfWidth > 0.0f)) return std::nullopt;
    const glm::vec3 direction =
        glm::normalize(-0.79f * f_.forward() + 0.47f * sign * f_.side() + 0.39f * f_.up());
    std::vector<glm::vec3> deltas(count(), glm::vec3(0.0f));
    for (size_t v = 0; v < count(); ++v) {
      if (!isSkin(g_.parts[v])) continue;
      const glm::vec3& p = g_.positions[v];
      const float w = fade(0.0f, 1.2f * halfWidth, glm::distance(p, corner));
      deltas[v] = kDimple * span_ * w * direction;
    }
    return deltas;
  }

  const ShapeGeometry& g_;
  const std::array<glm::vec3, kLandmarkCount>& l_;
  const LandmarkFrame& f_;
  float span_;
  std::span<const NamedDeltas> units_;
  std::vector<float> outer_;
};

}  // namespace

std::vector<NamedDeltas> arkitFromGeometry(std::span<const std::string> wanted, std::span<const NamedDeltas> units,
                                           const ShapeGeometry& geometry, std::vector<std::string>& unmade) {
  std::vector<NamedDeltas> shapes;
  if (!geometry.landmarks || !geometry.frame || !geometry.faceParts || geometry.parts.size() != geometry.positions.size()) {
    unmade.insert(unmade.end(), wanted.begin(), wanted.end());
    return shapes;
  }
  const Maker maker(units, geometry);
  for (const std::string& name : wanted) {
    std::optional<std::vector<glm::vec3>> deltas = maker.make(name);
    if (deltas)
      shapes.push_back({name, std::move(*deltas)});
    else
      unmade.push_back(name);
  }
  return shapes;
}

}  // namespace autorig
