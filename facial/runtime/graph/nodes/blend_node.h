#pragma once
// Blend of two inputs with an easing curve on the factor:
//   P = (1 - c(t)) P0 + c(t) P1,  t = factor clamped to [0,1].
// With the linear curve this is the plain linear blend P(t) = (1-t) P0 + t P1.
//
// JSON (graph_json.h): "blend": a, b, factor, curve
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

struct BlendNode {
  static constexpr std::string_view kType = "blend";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<BlendNode> read(const JsonNode& j, detail::NodeReader& r);

  NodeIndex a = kNoNode;  // P0
  NodeIndex b = kNoNode;  // P1
  FloatInput factor;      // t
  EasingCurve curve;      // linear by default

  static constexpr uint32_t kScratchPoses = 1;
  void inputs(std::vector<NodeIndex>& out) const { out.insert(out.end(), {a, b}); }
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
