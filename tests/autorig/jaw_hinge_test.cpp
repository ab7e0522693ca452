// The jaw's hinge from the landmarks: across the face, at the depth of the
// deeper of the jaw line's top points (an outline point the finder put on
// the cheek in front of the outline does not pull the hinge forward).
#include "autorig/jaw_hinge.h"

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "tests/autorig/transfer_fixture.h"

namespace {

TEST(JawHinge, TheDeeperTopPointSetsTheDepth) {
  std::optional<eng::Model> head = transfer_fixture::loadHead();
  ASSERT_TRUE(head);
  const autorig::FaceLandmarks landmarks = transfer_fixture::headSource(*head).landmarks;
  const autorig::LandmarkFrame frame(landmarks);
  const float span = frame.eyeSpan();
  const autorig::JawHinge hinge = autorig::estimateJawHinge(landmarks);
  EXPECT_LT(glm::distance(hinge.axis, frame.side()), 1e-5f);
  // Behind the jaw line's top points, a tenth of the span (the head is symmetric).
  const glm::vec3 middle = (landmarks.points[0] + landmarks.points[16]) * 0.5f;
  EXPECT_NEAR(glm::dot(middle - hinge.pivot, frame.forward()), 0.1f * span, 1e-3f * span);

  autorig::FaceLandmarks cheek = landmarks;  // point 0 taken on the cheek, in front
  cheek.points[0] += frame.forward() * (0.4f * span);
  const autorig::JawHinge same = autorig::estimateJawHinge(cheek);
  EXPECT_NEAR(glm::dot(same.pivot - hinge.pivot, frame.forward()), 0.0f, 1e-3f * span);

  autorig::FaceLandmarks deeper = landmarks;  // point 16 further back: the hinge follows it
  deeper.points[16] -= frame.forward() * (0.3f * span);
  const autorig::JawHinge back = autorig::estimateJawHinge(deeper);
  EXPECT_NEAR(glm::dot(hinge.pivot - back.pivot, frame.forward()), 0.3f * span, 0.05f * span);
}

}  // namespace
