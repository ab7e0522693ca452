#pragma once
// The bilinear pad's model: the study's bilinear interpolation of four
// keyframe poses (pose_jobs.h, BilinearPoseJob), s the vertical axis (row 1
// -> row 2), t the horizontal one (the "from" column -> the "to" column):
//   pose = s1 (t1 Q11 + t2 Q12) + s2 (t1 Q21 + t2 Q22),  s1 = 1 - s2, t1 = 1 - t2.
// Choosing a new "to" expression mid-way re-bases as the study (and the
// runtime's bilinear node) does: the pose on screen in each row becomes that
// row's "from" (Q_i1 = t1 Q_i1 + t2 Q_i2), t restarts at 0, so the face does
// not jump and moving t on blends toward the new expression.
// Poses are rig inputs (action units, then emotions); any equal length works.
#include <array>
#include <span>
#include <vector>

#include "engine/core/result.h"

namespace editor {

class BilinearPad {
 public:
  enum Corner : size_t { Q11 = 0, Q12 = 1, Q21 = 2, Q22 = 3 };  // row (s) then column (t)

  // All four poses, of one length.
  eng::Result<void> setCorners(std::array<std::vector<float>, 4> corners);
  // A "from" corner (Q11, Q21) is replaced as it is; a "to" corner (Q12, Q22) re-bases first.
  eng::Result<void> chooseCorner(Corner corner, std::span<const float> pose);
  // Clamped to [0, 1]; not-finite values are ignored.
  void setPosition(float s, float t);
  float s() const { return s_; }
  float t() const { return t_; }
  std::span<const float> corner(Corner c) const { return corners_[c]; }
  size_t poseSize() const { return corners_[Q11].size(); }
  // The blended pose (out.size() == poseSize()).
  eng::Result<void> pose(std::span<float> out) const;

 private:
  std::array<std::vector<float>, 4> corners_;
  float s_ = 0.0f, t_ = 0.0f;
};

}  // namespace editor
