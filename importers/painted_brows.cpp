#include "importers/painted_brows.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

// Brow shape in units of the distance between the eye centres (~63 mm on an
// adult, and -- unlike the fitted eyeball radius, which depends on how much
// of the ball a model hides -- the same on every face): u runs outward from
// the eye centre, v up. The head starts above the inner corner, leaving the
// glabella between the brows; the tail ends past the outer corner. The brow
// sits ~15 mm above the eye centre, on the orbital rim, ~10 mm thick at the
// head and thinning to the tail, arched at two thirds.
constexpr float kInnerEnd = -0.26f, kOuterEnd = 0.42f;
constexpr float kBaseHeight = 0.235f, kArch = 0.045f, kTailDrop = 0.03f;
constexpr float kHeadHalfThickness = 0.075f, kTailHalfThickness = 0.025f;

float coverage(const BrowFrame& f, const glm::vec3& p) {
  const glm::vec3 d = (p - f.eye) / f.scale;
  // Only the front of the face: the brow sits on the brow ridge, in front of
  // the eye centre, never on the temple or the back of the skull.
  if (glm::dot(d, f.forward) < -0.05f) return 0.0f;
  const float u = glm::dot(d, f.outward), v = glm::dot(d, f.up);
  const float t = (u - kInnerEnd) / (kOuterEnd - kInnerEnd);
  if (t <= 0.0f || t >= 1.0f) return 0.0f;
  const float arch = std::pow(std::sin(3.14159265f * std::pow(t, 0.75f)), 0.8f);
  const float centre = kBaseHeight + kArch * arch - kTailDrop * t;  // the tail drops a little
  const float half = kHeadHalfThickness + (kTailHalfThickness - kHeadHalfThickness) * t;
  // Soft edges, softer above (hairs thin out upward) than below.
  const float off = v - centre;
  const float across = 1.0f - glm::smoothstep(0.35f * half, off > 0.0f ? 1.2f * half : half, std::abs(off));
  // A blunt head, a tail that thins to nothing.
  const float along = glm::smoothstep(0.0f, 0.06f, t) * (1.0f - glm::smoothstep(0.8f, 1.0f, t));
  return across * along;
}

}  // namespace

std::vector<BrowFrame> browFrames(const Model& model, const std::vector<EyePrimitive>& eyes, int skinNode) {
  if (eyes.size() != 2) return {};
  const glm::mat4 toSkin = skinNode >= 0 ? glm::inverse(model.worldTransform(skinNode)) : glm::mat4(1.0f);
  glm::vec3 centre[2], gaze(0.0f);
  for (int i = 0; i < 2; ++i) {
    const EyePrimitive& e = eyes[size_t(i)];
    const glm::mat4 toWorld = e.node >= 0 ? model.worldTransform(e.node) : glm::mat4(1.0f);
    const glm::mat4 m = toSkin * toWorld;
    centre[i] = glm::vec3(m * glm::vec4(e.centre, 1.0f));
    gaze += glm::mat3(m) * e.gazeAxis;
  }
  const glm::vec3 up = glm::normalize(glm::mat3(toSkin) * glm::vec3(0.0f, 1.0f, 0.0f));
  glm::vec3 forward = gaze - up * glm::dot(gaze, up);
  const glm::vec3 across = centre[0] - centre[1];
  const float spacing = glm::length(across);
  if (glm::length(forward) < 1e-6f || !(spacing > 1e-6f) || !std::isfinite(spacing)) return {};
  forward = glm::normalize(forward);
  const glm::vec3 side = glm::normalize(glm::cross(up, forward));  // the face's own left
  std::vector<BrowFrame> frames;
  for (int i = 0; i < 2; ++i) {
    BrowFrame f;
    f.eye = centre[i];
    f.scale = spacing;
    f.up = up;
    f.forward = forward;
    const glm::vec3 away = centre[i] - 0.5f * (centre[0] + centre[1]);
    f.outward = glm::dot(away, side) >= 0.0f ? side : -side;
    frames.push_back(f);
  }
  return frames;
}

float browCoverage(const std::vector<BrowFrame>& frames, const glm::vec3& p) {
  float c = 0.0f;
  for (const BrowFrame& f : frames) c = std::max(c, coverage(f, p));
  return c;
}

glm::vec3 browColour() { return {0.045f, 0.030f, 0.022f}; }

}  // namespace importers
