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

// The RBF's control points for one deform part: position, displacement and
// name (for errors) of each, plus the moved landmarks' rest positions, which
// the mask's falloff measures from.
struct PartControls {
  std::vector<glm::vec3> positions, displacements, moved;
  std::vector<std::string> names;

  void add(const glm::vec3& position, const glm::vec3& displacement, const std::string& name) {
    positions.push_back(position);
    displacements.push_back(displacement);
    names.push_back(name);
  }
};

// The part's moves: each landmark displaced by `by` plus, with `to`, the way
// to another landmark. Marks each moved landmark in `isMoved`.
eng::Result<void> addMovedLandmarks(const DeformPartDef& part, const LandmarkPoints& landmarks, const std::string& where,
                                    PartControls& controls, std::vector<bool>& isMoved) {
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
    controls.add(landmarks.positions[i], by, d.landmark);
    controls.moved.push_back(landmarks.positions[i]);
  }
  return {};
}

// Pins the landmarks that do not move: those the part pins, and those its
// mask covers unless declared free.
void addStillLandmarks(const DeformPartDef& part, const LandmarkPoints& landmarks, const std::vector<bool>& isMoved,
                       PartControls& controls) {
  for (size_t i = 0; i < landmarks.names.size(); ++i) {
    if (isMoved[i]) continue;
    const std::string& name = landmarks.names[i];
    const bool pinned = std::find(part.pins.begin(), part.pins.end(), name) != part.pins.end();
    const bool free = std::find(part.free.begin(), part.free.end(), name) != part.free.end();
    const glm::vec3& p = landmarks.positions[i];
    const float covered = jawFactor(part.mask.jaw, landmarks.jawSide[i]) * sideFactor(part.mask.side, p.x) *
                          falloff(part.mask, p, controls.moved);
    if (pinned || (!free && covered > 0.02f)) controls.add(p, glm::vec3(0.0f), name);
  }
}

// Control points: moved landmarks, pinned landmarks, anchors, ring pins.
// Errors: an unresolved landmark, or two control points closer than 0.5 mm
// (the RBF system would be near singular).
eng::Result<PartControls> partControls(const DeformPartDef& part, const HeadRigSpec& spec, const LandmarkPoints& landmarks,
                                       const DeformableHead& head, const std::string& where) {
  PartControls controls;
  std::vector<bool> isMoved(landmarks.names.size(), false);
  if (auto r = addMovedLandmarks(part, landmarks, where, controls, isMoved); !r) return r.error();
  addStillLandmarks(part, landmarks, isMoved, controls);
  for (const AnchorDef& a : spec.anchors) controls.add(a.position, glm::vec3(0.0f), a.name);
  addRingPins(part.mask, head, controls.moved, controls.positions, controls.displacements, controls.names);
  const std::vector<glm::vec3>& at = controls.positions;
  for (size_t a = 0; a < at.size(); ++a)
    for (size_t b = a + 1; b < at.size(); ++b)
      if (glm::length(at[a] - at[b]) < 5e-4f)
        return eng::makeError(eng::ErrorKind::Malformed, where + ": control points \"" + controls.names[a] + "\" and \"" +
                              controls.names[b] + "\" are closer than 0.5 mm");
  return controls;
}

// Moves the vertices under the part's mask by the RBF through its control
// points, scaled by the mask's weight, adding to `total`.
eng::Result<void> deformPart(const DeformPartDef& part, const PartControls& controls, const HeadRigSpec& spec,
                             const DeformableHead& head, const std::string& where, std::vector<glm::vec3>& total) {
  std::vector<uint32_t> covered;
  std::vector<glm::vec3> points;
  std::vector<float> weights;
  for (size_t v = 0; v < head.positions.size(); ++v) {
    if (!part.mask.includes(head.parts[v])) continue;
    const glm::vec3& p = head.positions[v];
    const float w = jawFactor(part.mask.jaw, head.jawSide[v]) * sideFactor(part.mask.side, p.x) *
                    falloff(part.mask, p, controls.moved);
    if (w <= 0.0f) continue;
    covered.push_back(static_cast<uint32_t>(v));
    points.push_back(p);
    weights.push_back(w);
  }
  if (covered.empty()) return {};
  eng::Result<facial::RbfDeformer> deformer = facial::RbfDeformer::build(controls.positions, points, spec.kernel);
  if (!deformer) return deformer.error().prefixed(where + ": ");
  std::vector<glm::vec3> out(points.size());
  if (auto r = deformer->apply(controls.displacements, out, weights); !r) return r.error().prefixed(where + ": ");
  for (size_t k = 0; k < covered.size(); ++k) total[covered[k]] += out[k];
  return {};
}

// Eyelids slide over the eyeballs: a lid vertex ends at its rest distance
// from its eyeball's centre, so it travels around the ball, not through it.
// A morph target moves vertices along straight lines, though, and the chord
// of an arc dips toward the centre; lid skin (outside the ball at rest) ends
// a little further out instead, so that the chord's middle still clears
// the ball by kLidClearance at every weight.
void slideLidsOverEyeballs(const DeformableHead& head, std::vector<glm::vec3>& total) {
  for (size_t v = 0; v < total.size(); ++v) {
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
}

}  // namespace

int LandmarkPoints::find(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

eng::Result<std::vector<glm::vec3>> bakeActionUnit(const ActionUnitDef& unit, const HeadRigSpec& spec,
                                                   const LandmarkPoints& landmarks, const DeformableHead& head) {
  std::vector<glm::vec3> total(head.positions.size(), glm::vec3(0.0f));
  for (size_t partIndex = 0; partIndex < unit.parts.size(); ++partIndex) {
    const DeformPartDef& part = unit.parts[partIndex];
    const std::string where = spec.source + ": " + unit.name + " part " + std::to_string(partIndex);
    eng::Result<PartControls> controls = partControls(part, spec, landmarks, head, where);
    if (!controls) return controls.error();
    if (auto r = deformPart(part, *controls, spec, head, where, total); !r) return r.error();
  }
  slideLidsOverEyeballs(head, total);
  for (glm::vec3& d : total)
    if (glm::length(d) < kNegligible) d = glm::vec3(0.0f);
  return total;
}

}  // namespace bake
