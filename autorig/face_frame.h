#pragma once
// A face's own axes and feature lines, from its 68 landmarks: which way is
// the subject's left, up and forward, where the lips meet and where each
// eye's lids meet. The transfer labels both faces with it (upper lip against
// lower lip, upper lid against lower lid) and the ARKit shapes split their
// units with it (left against right, upper lip against lower lip).
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"

namespace autorig {

// Which side of a closing line a vertex is on, near that line; None away
// from the mouth and the eyes.
enum class FaceRegion : unsigned char {
  None,
  UpperLip,
  LowerLip,
  RightUpperLid,  // the subject's right eye (landmarks 36-41)
  RightLowerLid,
  LeftUpperLid,  // landmarks 42-47
  LeftLowerLid,
};

// The region across the closing line from `region` (UpperLip <-> LowerLip...);
// None for None.
FaceRegion opposite(FaceRegion region);

// Whether landmark `index` draws a lid line (where the lids meet and end: 36-47).
bool onLidLine(size_t index);
// Whether landmark `index` is a mouth corner (where the lips' lines end: 48, 54, 60, 64).
bool atMouthCorner(size_t index);

class LandmarkFrame {
 public:
  explicit LandmarkFrame(const FaceLandmarks& landmarks);

  const glm::vec3& origin() const { return origin_; }  // between the eyes and the mouth
  const glm::vec3& side() const { return side_; }      // towards the subject's left (36 -> 45)
  const glm::vec3& up() const { return up_; }          // chin -> brows, square to side
  const glm::vec3& forward() const { return forward_; }  // out of the face
  // The distance between the outer eye corners: the face's unit of size.
  float eyeSpan() const { return eyeSpan_; }

  // Across the midline in eye spans: < 0 the subject's right, > 0 the left.
  float sideOf(const glm::vec3& p) const { return glm::dot(p - origin_, side_) / eyeSpan_; }
  // Above (> 0) or below the line where the lips meet, in eye spans.
  float aboveLipLine(const glm::vec3& p) const;
  // `margin` (optional) receives how far p is from the closing line, in eye spans.
  FaceRegion region(const glm::vec3& p, float* margin = nullptr) const;

 private:
  struct Line {  // a closing line as a polyline in the face plane (side, up)
    std::vector<glm::vec2> points;  // sorted by side
    glm::vec2 centre{0.0f};
    float halfWidth = 0.0f;  // of the region it labels, along side
    float halfHeight = 0.0f;  // and across
    // A parabola between its ends instead of the polyline (the lips' line):
    // y = c0 + c1 u + c2 u^2, u = (x - centre.x) / halfSpan, half the ends' spread.
    bool parabola = false;
    float halfSpan = 0.0f;
    glm::vec3 coefficients{0.0f};
    void fitParabola();
    float heightAt(float x) const;
  };
  glm::vec2 plane(const glm::vec3& p) const { return {glm::dot(p - origin_, side_), glm::dot(p - origin_, up_)}; }
  Line makeLine(const FaceLandmarks& landmarks, std::span<const std::array<int, 2>> pairs) const;

  glm::vec3 origin_{0.0f}, side_{1, 0, 0}, up_{0, 1, 0}, forward_{0, 0, 1};
  float eyeSpan_ = 1.0f;
  Line lips_, rightEye_, leftEye_;
};

}  // namespace autorig
