#include "autorig/face_frame.h"

#include <algorithm>
#include <cmath>

namespace autorig {
namespace {

// Landmark pairs whose midpoints trace each closing line (a pair of one
// index is a corner).
constexpr std::array<std::array<int, 2>, 7> kLipLine{{{48, 48}, {60, 60}, {61, 67}, {62, 66}, {63, 65}, {64, 64}, {54, 54}}};
constexpr std::array<std::array<int, 2>, 4> kRightLidLine{{{36, 36}, {37, 41}, {38, 40}, {39, 39}}};
constexpr std::array<std::array<int, 2>, 4> kLeftLidLine{{{42, 42}, {43, 47}, {44, 46}, {45, 45}}};

bool onLine(std::span<const std::array<int, 2>> pairs, size_t index) {
  return std::any_of(pairs.begin(), pairs.end(), [&](const std::array<int, 2>& p) { return size_t(p[0]) == index || size_t(p[1]) == index; });
}

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& fallback) {
  float length = glm::length(v);
  return length > 1e-12f ? v / length : fallback;
}

}  // namespace

FaceRegion opposite(FaceRegion region) {
  switch (region) {
    case FaceRegion::UpperLip: return FaceRegion::LowerLip;
    case FaceRegion::LowerLip: return FaceRegion::UpperLip;
    case FaceRegion::RightUpperLid: return FaceRegion::RightLowerLid;
    case FaceRegion::RightLowerLid: return FaceRegion::RightUpperLid;
    case FaceRegion::LeftUpperLid: return FaceRegion::LeftLowerLid;
    case FaceRegion::LeftLowerLid: return FaceRegion::LeftUpperLid;
    case FaceRegion::None: break;
  }
  return FaceRegion::None;
}

bool onLidLine(size_t index) { return onLine(kRightLidLine, index) || onLine(kLeftLidLine, index); }

bool atMouthCorner(size_t index) {
  // The lip line's ends: its pairs of one index.
  return std::any_of(kLipLine.begin(), kLipLine.end(), [&](const std::array<int, 2>& p) { return p[0] == p[1] && size_t(p[0]) == index; });
}

LandmarkFrame::LandmarkFrame(const FaceLandmarks& landmarks) {
  const auto& p = landmarks.points;
  const glm::vec3 rightEye = (p[36] + p[39]) * 0.5f, leftEye = (p[42] + p[45]) * 0.5f;
  const glm::vec3 mouth = (p[48] + p[54]) * 0.5f;
  eyeSpan_ = std::max(glm::length(p[45] - p[36]), 1e-6f);
  side_ = normalizedOr(p[45] - p[36], {1, 0, 0});
  const glm::vec3 rise = (rightEye + leftEye) * 0.5f - p[8];
  up_ = normalizedOr(rise - glm::dot(rise, side_) * side_, {0, 1, 0});
  forward_ = glm::cross(side_, up_);
  origin_ = ((rightEye + leftEye) * 0.5f + mouth) * 0.5f;

  lips_ = makeLine(landmarks, kLipLine);
  // The lips' line is the parabola nearest its points (least squares), not
  // the polyline through them: dlib's inner-lip points on a face it does not
  // know are often 0.02 eye spans off, and one lower point lifted over an
  // upper one bent the polyline by a lip's thickness there, so the skin inside
  // that lip took the other lip's motion (Ready Player Me's upper lip pulled
  // into its dropped jaw's mouth in one draw of six).
  lips_.fitParabola();
  lips_.halfWidth = 0.5f * glm::length(p[54] - p[48]) * 1.3f;
  lips_.halfHeight = 0.5f * glm::length(p[8] - p[33]);
  rightEye_ = makeLine(landmarks, kRightLidLine);
  leftEye_ = makeLine(landmarks, kLeftLidLine);
  for (Line* eye : {&rightEye_, &leftEye_}) {
    float width = eye->points.back().x - eye->points.front().x;
    eye->halfWidth = 0.5f * width * 1.4f;
    eye->halfHeight = 0.7f * width;
  }
}

LandmarkFrame::Line LandmarkFrame::makeLine(const FaceLandmarks& landmarks, std::span<const std::array<int, 2>> pairs) const {
  Line line;
  for (const auto& pair : pairs)
    line.points.push_back(plane((landmarks.points[static_cast<size_t>(pair[0])] + landmarks.points[static_cast<size_t>(pair[1])]) * 0.5f));
  std::sort(line.points.begin(), line.points.end(), [](const glm::vec2& a, const glm::vec2& b) { return a.x < b.x; });
  line.centre = (line.points.front() + line.points.back()) * 0.5f;
  return line;
}

void LandmarkFrame::Line::fitParabola() {
  halfSpan = 0.5f * (points.back().x - points.front().x);
  if (!(halfSpan > 0.0f)) return;
  glm::dmat3 normal(0.0);
  glm::dvec3 rhs(0.0);
  for (const glm::vec2& q : points) {
    const double u = double((q.x - centre.x) / halfSpan);
    const glm::dvec3 row(1.0, u, u * u);
    normal += glm::outerProduct(row, row);
    rhs += row * double(q.y);
  }
  if (std::abs(glm::determinant(normal)) < 1e-9) return;  // fewer than three distinct columns
  coefficients = glm::vec3(glm::inverse(normal) * rhs);
  parabola = true;
}

float LandmarkFrame::Line::heightAt(float x) const {
  if (parabola) {
    const float u = (std::clamp(x, points.front().x, points.back().x) - centre.x) / halfSpan;
    return coefficients.x + coefficients.y * u + coefficients.z * u * u;
  }
  if (x <= points.front().x) return points.front().y;
  for (size_t i = 1; i < points.size(); ++i) {
    if (x > points[i].x) continue;
    float span = points[i].x - points[i - 1].x;
    float t = span > 1e-12f ? (x - points[i - 1].x) / span : 0.0f;
    return points[i - 1].y + t * (points[i].y - points[i - 1].y);
  }
  return points.back().y;
}

float LandmarkFrame::aboveLipLine(const glm::vec3& p) const {
  glm::vec2 q = plane(p);
  return (q.y - lips_.heightAt(q.x)) / eyeSpan_;
}

FaceRegion LandmarkFrame::region(const glm::vec3& p, float* margin) const {
  // Only the front of the face: the back of the head projects onto the same lines.
  const float depth = glm::dot(p - origin_, forward_);
  if (depth < -0.6f * eyeSpan_) return FaceRegion::None;
  const glm::vec2 q = plane(p);
  struct Candidate {
    const Line* line;
    FaceRegion upper, lower;
  };
  for (const Candidate& c : {Candidate{&lips_, FaceRegion::UpperLip, FaceRegion::LowerLip},
                             Candidate{&rightEye_, FaceRegion::RightUpperLid, FaceRegion::RightLowerLid},
                             Candidate{&leftEye_, FaceRegion::LeftUpperLid, FaceRegion::LeftLowerLid}}) {
    if (std::abs(q.x - c.line->centre.x) > c.line->halfWidth) continue;
    float above = q.y - c.line->heightAt(q.x);
    if (std::abs(above) > c.line->halfHeight) continue;
    if (margin) *margin = std::abs(above) / eyeSpan_;
    return above >= 0.0f ? c.upper : c.lower;
  }
  return FaceRegion::None;
}

}  // namespace autorig
