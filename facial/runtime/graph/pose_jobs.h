#pragma once
// The arithmetic of poses: small jobs over spans of weights (ozz style).
// Validate() names the sizes that do not fit (InvalidArgument: the caller's
// spans, not a file); Run() validates, then works in place without
// allocating. All spans of one job have the same length (a pose: the
// channels, then the graph's lanes), except where noted.
#include <span>

#include "engine/core/result.h"

namespace facial {

// out = (1 - t) a + t b. out may alias a or b.
struct LerpPoseJob {
  std::span<const float> a, b;
  float t = 0;
  std::span<float> out;
  eng::Result<void> Validate() const;
  bool Run() const;
};

// out += weight * input.
struct AccumulatePoseJob {
  std::span<const float> input;
  float weight = 0;
  std::span<float> out;
  eng::Result<void> Validate() const;
  bool Run() const;
};

// The study's bilinear blend of two face shapes (rows) x two expressions (columns):
//   out = s1 (t1 q11 + t2 q12) + s2 (t1 q21 + t2 q22),  s1 = 1 - s2, t1 = 1 - t2.
// out may alias any input.
struct BilinearPoseJob {
  std::span<const float> q11, q12, q21, q22;
  float s2 = 0;  // shape axis: 0 = shape 1, 1 = shape 2
  float t2 = 0;  // expression axis: 0 = expression 1, 1 = expression 2
  std::span<float> out;
  eng::Result<void> Validate() const;
  bool Run() const;
};

// Additive layer: out[c] = clamp(base[c] + weight * mask[c] * layer[c], 0, 1)
// for the first mask.size() entries (the channels); the remaining entries
// (lanes) are copied from base. out may alias base.
struct AdditivePoseJob {
  std::span<const float> base, layer, mask;
  float weight = 1;
  std::span<float> out;
  eng::Result<void> Validate() const;
  bool Run() const;
};

}  // namespace facial
