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
//
// JSON (graph_json.h): "controlMap": neutral, up (+y, E1), down (-y, E2), right (+x, E3), left (-x, E4), x, y
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

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
  static constexpr std::string_view kType = "controlMap";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<ControlMapNode> read(const JsonNode& j, detail::NodeReader& r);

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
