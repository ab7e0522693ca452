#include "autorig/jaw_hinge.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "autorig/face_frame.h"

namespace autorig {
namespace {

// How far behind the jaw line's top points the condyles sit, in eye spans.
constexpr float kHingeDepth = 0.1f;

}  // namespace

// The jaw line's top points lie on the face's outline, where the finder takes
// the vertex nearest in the picture at whatever depth: the cheek in front of
// the outline, never a point behind the joint (Ready Player Me's 0 lies 0.39
// eye span in front of its 16). So the deeper of the two sets the depth.
JawHinge estimateJawHinge(const FaceLandmarks& landmarks) {
  const LandmarkFrame frame(landmarks);
  const glm::vec3& right = landmarks.points[0];
  const glm::vec3& left = landmarks.points[16];
  const glm::vec3 middle = (right + left) * 0.5f;
  const float deeper = std::min(glm::dot(right - middle, frame.forward()), glm::dot(left - middle, frame.forward()));
  return JawHinge{.pivot = middle + frame.forward() * (deeper - kHingeDepth * frame.eyeSpan()), .axis = frame.side()};
}

float hingeAngle(const JawHinge& hinge, const glm::vec3& point, const glm::vec3& displacement) {
  auto flat = [&](const glm::vec3& v) { return v - glm::dot(v, hinge.axis) * hinge.axis; };
  const glm::vec3 from = flat(point - hinge.pivot), to = flat(point + displacement - hinge.pivot);
  return std::atan2(glm::dot(glm::cross(from, to), hinge.axis), glm::dot(from, to));
}

glm::vec3 turnAboutHinge(const JawHinge& hinge, float angle, const glm::vec3& point) {
  const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), angle, hinge.axis));
  return hinge.pivot + turn * (point - hinge.pivot) - point;
}

}  // namespace autorig
