#include "editor/bilinear_pad.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "facial/runtime/graph/pose_jobs.h"

namespace editor {

namespace {
eng::Error sizeProblem(size_t expected, size_t got) {
  return eng::makeError(eng::ErrorKind::InvalidArgument, "bilinear pad: a pose of " + std::to_string(got) +
                                                             " weights, the pad's poses have " + std::to_string(expected));
}
}  // namespace

eng::Result<void> BilinearPad::setCorners(std::array<std::vector<float>, 4> corners) {
  for (const auto& c : corners)
    if (c.size() != corners[0].size()) return sizeProblem(corners[0].size(), c.size());
  corners_ = std::move(corners);
  return {};
}

eng::Result<void> BilinearPad::chooseCorner(Corner corner, std::span<const float> pose) {
  if (pose.size() != poseSize()) return sizeProblem(poseSize(), pose.size());
  if (corner == Q12 || corner == Q22) {
    // Re-base on what is on screen, row by row: from_i = t1 from_i + t2 to_i.
    for (const auto& [from, to] : {std::pair{Q11, Q12}, std::pair{Q21, Q22}})
      facial::LerpPoseJob{.a = corners_[from], .b = corners_[to], .t = t_, .out = corners_[from]}.Run();
    t_ = 0.0f;
  }
  corners_[corner].assign(pose.begin(), pose.end());
  return {};
}

void BilinearPad::setPosition(float s, float t) {
  if (std::isfinite(s)) s_ = std::clamp(s, 0.0f, 1.0f);
  if (std::isfinite(t)) t_ = std::clamp(t, 0.0f, 1.0f);
}

eng::Result<void> BilinearPad::pose(std::span<float> out) const {
  const facial::BilinearPoseJob job{.q11 = corners_[Q11], .q12 = corners_[Q12], .q21 = corners_[Q21], .q22 = corners_[Q22],
                                    .s2 = s_, .t2 = t_, .out = out};
  ENG_TRY(job.Validate());
  job.Run();
  return {};
}

}  // namespace editor
