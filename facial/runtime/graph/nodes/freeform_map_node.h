#pragma once
// Freeform 2D map: N emotion poles anywhere in the plane (e.g. the six basic
// emotions around a valence/arousal circle) and neutral at the centre (0,0).
// Weights are Johansen's gradient bands (the scheme behind Unity's 2D
// Freeform Cartesian blend trees):
//   h_i(p) = min_{j != i} clamp(1 - (p - p_i).(p_j - p_i) / |p_j - p_i|^2, 0, 1),
//   w_i = h_i / sum_k h_k.
// At pole i, h_i = 1 and every other h_j = 0, so each pole is reproduced
// exactly; the weights are continuous and piecewise smooth (Lipschitz with a
// constant set by the closest pair of poles), stay in [0,1] and sum to 1, and
// a pole only mixes with its neighbours. The cursor is clamped to the disc
// through the farthest pole.
//
// JSON (graph_json.h): "freeformMap": neutral, poles [{"at": [x, y], "node": {...}}], x, y
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

inline constexpr size_t kMaxFreeformPoles = 32;

// Gradient-band weights of `points` at p (no clamping of p). weights.size() == points.size().
void gradientBandWeights(std::span<const glm::vec2> points, glm::vec2 p, std::span<float> weights);

struct FreeformPole {
  glm::vec2 position{0.0f};
  NodeIndex node = kNoNode;
};

struct FreeformMapNode {
  static constexpr std::string_view kType = "freeformMap";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<FreeformMapNode> read(const JsonNode& j, detail::NodeReader& r);

  NodeIndex neutral = kNoNode;      // at the origin
  std::vector<FreeformPole> poles;  // 1..kMaxFreeformPoles, distinct, away from the origin
  FloatInput x, y;

  // Derived at build: neutral first, then the poles.
  std::vector<glm::vec2> points;
  std::vector<NodeIndex> nodes;
  float radius = 1;  // cursor clamp

  // Weights (neutral first) at cursor (x, y) after clamping to the disc.
  void weightsAt(glm::vec2 cursor, std::span<float> weights) const;

  static constexpr uint32_t kScratchPoses = 1;
  void inputs(std::vector<NodeIndex>& out) const;
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
