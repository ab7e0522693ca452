#pragma once
// The study's 2D control map: four emotion poles on the axes, neutral at the
// centre. From the cursor (x, y), exactly as the study's pseudo-code:
//   x >= 0: wE3 = x     x <= 0: wE4 = |x|
//   y >= 0: wE1 = y     y <= 0: wE2 = |y|
//   wNeutral = 1 - (wE1 + wE2 + wE3 + wE4)
// The cursor is first clamped to the unit square [-1,1]^2 and then, if it
// lies outside the diamond |x| + |y| <= 1, pulled back along its ray onto the
// diamond's edge (x, y) / (|x| + |y|). On the diamond the weights are a convex
// combination (all >= 0, sum 1): a corner of the square would otherwise ask
// for wNeutral = -1, a face pushed past two full emotions at once.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"

namespace facial {

struct ControlMapWeights {
  float x = 0, y = 0;  // the cursor after clamping
  float neutral = 1;
  float e1 = 0;  // +y
  float e2 = 0;  // -y
  float e3 = 0;  // +x
  float e4 = 0;  // -x
};
ControlMapWeights controlMapWeights(float x, float y);

struct ControlMapNode {
  NodeIndex neutral = kNoNode;
  NodeIndex e1 = kNoNode;  // +y ("up")
  NodeIndex e2 = kNoNode;  // -y ("down")
  NodeIndex e3 = kNoNode;  // +x ("right")
  NodeIndex e4 = kNoNode;  // -x ("left")
  FloatInput x, y;

  static constexpr uint32_t kScratchPoses = 1;
  void inputs(std::vector<NodeIndex>& out) const { out.insert(out.end(), {neutral, e1, e2, e3, e4}); }
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
