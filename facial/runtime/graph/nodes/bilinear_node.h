#pragma once
// The study's bilinear blend between face shapes and expressions. Keyframes
// form a 2 x K grid: row i is face shape i, column j expression j (Q_ij).
// With the current expression pair (from, to) and blend t2 = c(progress):
//   Pf = s1 (t1 Q1from + t2 Q1to) + s2 (t1 Q2from + t2 Q2to),  s1+s2 = t1+t2 = 1.
// Selecting a new expression mid-way re-bases as the study does: the pair on
// screen becomes the new "from" (Q13 = t1 Q11 + t2 Q12, Q23 = t1 Q21 + t2 Q22)
// and progress restarts toward the new column, so the face does not jump.
//
// JSON (graph_json.h): "bilinear": shapes [[Q11, Q12, ...], [Q21, Q22, ...]], shape, expression (float parameter), duration, curve
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

struct BilinearNode {
  static constexpr std::string_view kType = "bilinear";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<BilinearNode> read(const JsonNode& j, detail::NodeReader& r);

  std::vector<NodeIndex> shape1;            // Q11, Q12, ..., Q1K
  std::vector<NodeIndex> shape2;            // Q21, Q22, ..., Q2K
  FloatInput shape;                         // s2: 0 = face shape 1, 1 = face shape 2 (clamped)
  ParameterIndex expression = kNoParameter; // float parameter: column to show (rounded, clamped to [0, K-1])
  float duration = 0.5f;                    // seconds from one expression to the next
  EasingCurve curve;                        // t2 = c(progress)

  struct State {
    std::vector<float> from1, from2;  // Q13 and Q23: the re-based "from" pair, one pose each
    uint32_t target = 0;              // column blended toward
    float progress = 1;               // [0,1]
    bool started = false;             // false until the first frame picks the initial column
  };

  static constexpr uint32_t kScratchPoses = 2;
  void inputs(std::vector<NodeIndex>& out) const;
  eng::Result<void> prepare(const BuildContext& ctx);
  State makeState(const GraphDefinition& definition, NodeIndex self, uint64_t seed) const;
  void reset(State& state) const;
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
