#pragma once
// The almond-shaped eye opening of one eye, as angles around the eyeball
// centre. Shared by the skin builder (lid margins), the landmarks (lid and
// corner points) and the eyeball painter.
#include <vector>

#include <glm/glm.hpp>

#include "bake/head/head_proportions.h"

namespace bake {

class EyeOpening {
 public:
  // side: +1 for the left eye (+X), -1 for the right eye.
  EyeOpening(const HeadProportions& proportions, float side);

  float side() const { return side_; }
  const glm::vec3& centre() const { return centre_; }
  float radius() const { return radius_; }

  // Angles (degrees, lateral a / vertical b) of a point on the upper or lower
  // lid margin; t runs from the inner corner (0) to the outer corner (1).
  glm::vec2 upperLid(float t) const;
  glm::vec2 lowerLid(float t) const;
  // Centre of the almond in angles (halfway between the lid extremes).
  glm::vec2 middle() const { return middle_; }
  glm::vec2 halfExtent() const { return halfExtent_; }

  // Unit direction from the eyeball centre for angles (degrees).
  glm::vec3 direction(const glm::vec2& angles) const;
  // Angles (degrees) of a direction from the eyeball centre.
  glm::vec2 angles(const glm::vec3& direction) const;

  // The margin point in the direction of polar angle `psi` (radians) around
  // middle(), measured in coordinates scaled by halfExtent() so the almond is
  // near-circular. Returns angles and whether it lies on the upper lid.
  glm::vec2 marginAt(float psi, bool* upper = nullptr) const;
  // Polar angle (radians) of `angles` around middle() in the same scaled coordinates.
  float polarAngle(const glm::vec2& angles) const;

 private:
  float side_;
  glm::vec3 centre_;
  float radius_;
  glm::vec2 inner_, outer_;
  float upperHeight_, lowerDepth_;
  glm::vec2 middle_, halfExtent_;
  // Dense closed polyline (upper arc inner->outer, then lower arc outer->inner)
  // with each sample's polar angle, for marginAt().
  std::vector<glm::vec2> loop_;
  std::vector<bool> loopUpper_;
  std::vector<float> loopPsi_;
};

}  // namespace bake
