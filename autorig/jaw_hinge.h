#pragma once
// The jaw's hinge (the temporomandibular axis), estimated from the landmarks:
// the line across the face through the jaw line's top points 0 and 16, at the
// deeper one's depth, set back into the head by a tenth of the eye span. A jaw unit turns the lower teeth and the tongue
// about it rigidly, by the angle the source face's chin turns about its own.
#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"

namespace autorig {

struct JawHinge {
  glm::vec3 pivot{0.0f};
  glm::vec3 axis{1.0f, 0.0f, 0.0f};  // towards the subject's left
};

JawHinge estimateJawHinge(const FaceLandmarks& landmarks);

// The angle (radians, about hinge.axis) that takes `point` to `point + displacement`,
// measured in the plane square to the axis.
float hingeAngle(const JawHinge& hinge, const glm::vec3& point, const glm::vec3& displacement);

// The displacement of `point` turned by `angle` about the hinge.
glm::vec3 turnAboutHinge(const JawHinge& hinge, float angle, const glm::vec3& point);

}  // namespace autorig
