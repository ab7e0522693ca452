#include "bake/head/au_baker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/common.hpp>

#include "facial/runtime/rbf.h"

namespace bake {
namespace {

// Deltas shorter than this (30 microns, far below a pixel) are treated as no
// motion, so targets stay sparse where the masks fade out.
constexpr float kNegligible = 3e-5f;

// How far lid skin stays outside the eyeball while a lid target blends in.
constexpr float kLidClearance = 0.0004f;

float jawFactor(MaskDef::Jaw jaw, float jawSide) {
  switch (jaw) {
    case MaskDef::Jaw::Upper: return 1.0f - jawSide;
    case MaskDef::Jaw::Lower: return jawSide;
    case MaskDef::Jaw::Any: return 1.0f;
  }
  return 1.0f;
}

float sideFactor(MaskDef::Side side, float x) {
  // A 12 mm blend across the midline keeps one-sided units smooth there.
  switch (side) {
    case MaskDef::Side::Left: return glm::smoothstep(-0.006f, 0.006f, x);
    case MaskDef::Side::Right: return glm::smoothstep(0.006f, -0.006f, x);
    case MaskDef::Side::Both: return 1.0f;
  }
  return 1.0f;
}

float falloff(const MaskDef& mask, const glm::vec3& p, const std::vector<glm::vec3>& moved) {
  float nearest = std::numeric_limits<float>::max();
  for (const glm::vec3& m : moved) nearest = std::min(nearest, glm::length(p - m));
  return 1.0f - glm::smoothstep(mask.radius, mask.radius + mask.feather, nearest);
}

// Still points on the skin where the mask's weight reaches zero (radius +
// feather from the nearest moved landmark), a few millimetres apart. Without
// them the displacement is still large where the weight fades it out, and
// the skin bunches into a ring-shaped fold around the moved landmarks; with
// them the interpolation itself has come down to nothing there.
void addRingPins(const MaskDef& mask, const DeformableHead& head, const std::vector<glm::vec3>& moved,
                 std::vector<glm::vec3>& controls, std::vector<glm::vec3>& displacements,
                 std::vector<std::string>& names) {
  if (!mask.includes(HeadPart::Skin)) return;
  const float ring = mask.radius + mask.feather;
  constexpr float spacing = 0.004f, band = 0.0008f;
  std::vector<glm::vec3> chosen;
  for (size_t v = 0; v < head.positions.size(); ++v) {
    if (head.parts[v] != HeadPart::Skin) continue;
    const glm::vec3& p = head.positions[v];
    if (jawFactor(mask.jaw, head.jawSide[v]) * sideFactor(mask.side, p.x) < 0.5f) continue;
    float nearest = std::numeric_limits<float>::max();
    for (const glm::vec3& m : moved) nearest = std::min(nearest, glm::length(p - m));
    if (std::abs(nearest - ring) > band) continue;
    bool crowded = false;
    for (const glm::vec3& c : chosen) crowded |= glm::length(c - p) < spacing;
    for (const glm::vec3& c : controls) crowded |= glm::length(c - p) < 0.5f * spacing;
    if (crowded) continue;
    chosen.push_back(p);
    controls.push_back(p);
    displacements.push_back(glm::vec3(0.0f));
    names.push_back("ring " + std::to_string(chosen.size()));
  }
}

}  // namespace

int LandmarkPoints::find(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

eng::Result<std::vector<glm::vec3>> bakeActionUnit(const ActionUnitDef& unit, const HeadRigSpec& spec,
                                                   const LandmarkPoints& landmarks, const DeformableHead& head) {
  const size_t n = head.positions.size();
  std::vector<glm::vec3> total(n, glm::vec3(0.0f));
  for (size_t partIndex = 0; partIndex < unit.parts.size(); ++partIndex) {
    const DeformPartDef& part = unit.parts[partIndex];
    const std::string where = spec.source + ": " + unit.name + " part " + std::to_string(partIndex);

    // Control points: moved landmarks, pinned landmarks, anchors.
    std::vector<glm::vec3> controls, displacements, moved;
    std::vector<std::string> controlNames;
    std::vector<bool> isMoved(landmarks.names.size(), false);
    for (const DisplacementDef& d : part.moves) {
      const int i = landmarks.find(d.landmark);
      if (i < 0) return eng::makeError(eng::ErrorKind::Malformed, where + ": landmark \"" + d.landmark + "\" was not resolved");
      glm::vec3 by = d.by;
      if (!d.to.empty()) {
        const int j = landmarks.find(d.to);
        if (j < 0) return eng::makeError(eng::ErrorKind::Malformed, where + ": landmark \"" + d.to + "\" was not resolved");
        by += landmarks.positions[j] - landmarks.positions[i];
      }
      isMoved[i] = true;
      controls.push_back(landmarks.positions[i]);
      displacements.push_back(by);
      moved.push_back(landmarks.positions[i]);
      controlNames.push_back(d.landmark);
    }
    for (size_t i = 0; i < landmarks.names.size(); ++i) {
      if (isMoved[i]) continue;
      const std::string& name = landmarks.names[i];
      const bool pinned = std::find(part.pins.begin(), part.pins.end(), name) != part.pins.end();
      const bool free = std::find(part.free.begin(), part.free.end(), name) != part.free.end();
      // A landmark the mask covers stays put unless declared free.
      const glm::vec3& p = landmarks.positions[i];
      const float covered = jawFactor(part.mask.jaw, landmarks.jawSide[i]) * sideFactor(part.mask.side, p.x) *
                            falloff(part.mask, p, moved);
      if (pinned || (!free && covered > 0.02f)) {
        controls.push_back(p);
        displacements.push_back(glm::vec3(0.0f));
        controlNames.push_back(name);
      }
    }
    for (const AnchorDef& a : spec.anchors) {
      controls.push_back(a.position);
      displacements.push_back(glm::vec3(0.0f));
      controlNames.push_back(a.name);
    }
    addRingPins(part.mask, head, moved, controls, displacements, controlNames);
    for (size_t a = 0; a < controls.size(); ++a)
      for (size_t b = a + 1; b < controls.size(); ++b)
        if (glm::length(controls[a] - controls[b]) < 5e-4f)
          return eng::makeError(eng::ErrorKind::Malformed, where + ": control points \"" + controlNames[a] + "\" and \"" + controlNames[b] +
                                "\" are closer than 0.5 mm");

    // Vertices under the mask.
    std::vector<uint32_t> covered;
    std::vector<glm::vec3> points;
    std::vector<float> weights;
    for (size_t v = 0; v < n; ++v) {
      if (!part.mask.includes(head.parts[v])) continue;
      const glm::vec3& p = head.positions[v];
      const float w = jawFactor(part.mask.jaw, head.jawSide[v]) * sideFactor(part.mask.side, p.x) *
                      falloff(part.mask, p, moved);
      if (w <= 0.0f) continue;
      covered.push_back(static_cast<uint32_t>(v));
      points.push_back(p);
      weights.push_back(w);
    }
    if (covered.empty()) continue;
    eng::Result<facial::RbfDeformer> deformer = facial::RbfDeformer::build(controls, points, spec.kernel);
    if (!deformer) return deformer.error().prefixed(where + ": ");
    std::vector<glm::vec3> out(points.size());
    if (auto r = deformer->apply(displacements, out, weights); !r) return r.error().prefixed(where + ": ");
    for (size_t k = 0; k < covered.size(); ++k) total[covered[k]] += out[k];
  }

  // Eyelids slide over the eyeballs: a lid vertex ends at its rest distance
  // from its eyeball's centre, so it travels around the ball, not through it.
  // A morph target moves vertices along straight lines, though, and the chord
  // of an arc dips toward the centre; lid skin (outside the ball at rest) ends
  // a little further out instead, so that the chord's middle still clears
  // the ball by kLidClearance at every weight.
  for (size_t v = 0; v < n; ++v) {
    if (head.lidEye[v] < 0 || head.lidSlide[v] <= 0.0f) continue;
    const DeformableHead::Eye& eye = head.eyes[static_cast<size_t>(head.lidEye[v])];
    const glm::vec3 rest = head.positions[v];
    const glm::vec3 from = rest - eye.centre;
    const float radius = glm::length(from);
    const glm::vec3 dir = rest + total[v] - eye.centre;
    const float len = glm::length(dir);
    if (len <= 0.0f || radius <= 0.0f) continue;
    float endRadius = radius;
    if (radius > eye.radius) {
      // |a + b| / 2 >= m for |a| = radius, |b| = endRadius, angle theta between.
      const float m = eye.radius + kLidClearance;
      const float cosTheta = std::clamp(glm::dot(from, dir) / (radius * len), -1.0f, 1.0f);
      const float disc = radius * radius * cosTheta * cosTheta - radius * radius + 4.0f * m * m;
      if (disc > 0.0f) endRadius = std::max(radius, -radius * cosTheta + std::sqrt(disc));
    }
    const glm::vec3 slid = eye.centre + dir * (endRadius / len);
    total[v] = glm::mix(total[v], slid - rest, head.lidSlide[v]);
  }
  for (glm::vec3& d : total)
    if (glm::length(d) < kNegligible) d = glm::vec3(0.0f);
  return total;
}

}  // namespace bake
