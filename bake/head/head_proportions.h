#pragma once
// Proportions of the built-in head: the few numbers a look developer tunes.
// Metres, glTF axes: +Y up, the face looks toward +Z, the subject's left is +X.
// Only left-side features are stored; the right side is the mirror (x -> -x).
#include <glm/glm.hpp>

namespace bake {

struct HeadProportions {
  // Rays that place the skin grid start here (inside the head, above the
  // nose base so the nose underside still faces away from it).
  glm::vec3 gridCentre{0.0f, -0.018f, 0.0f};

  glm::vec3 eyeCentre{0.0335f, 0.0090f, 0.0632f};  // left eyeball centre
  float eyeRadius = 0.0150f;
  float upperLidThickness = 0.0013f;  // lid skin above the eyeball surface
  float lowerLidThickness = 0.0008f;
  // Eye opening (almond) in degrees around the eyeball centre, seen from the
  // front: lateral angle a (+ toward the outer corner), vertical angle b.
  float innerCornerA = -52.0f, innerCornerB = -5.0f;
  float outerCornerA = 57.0f, outerCornerB = 4.0f;
  float upperLidHeight = 20.0f;  // degrees above the corner line at the peak
  float lowerLidDepth = 17.5f;   // degrees below the corner line at the lowest point
  float irisAngle = 29.0f;       // iris radius, degrees from the gaze axis
  float pupilAngle = 12.0f;

  // Mouth: the lip seam is the cone of rays from gridCentre through this point.
  glm::vec3 mouthSeamCentre{0.0f, -0.0505f, 0.0985f};  // on the closed lips
  float mouthHalfWidth = 0.0232f;  // x of the lip corners

  float crownY = 0.121f;
  float neckBottomY = -0.160f;
};

}  // namespace bake
