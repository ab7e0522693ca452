#include "facial/runtime/graph/nodes/freeform_map_node.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"

namespace facial {

using detail::NodeReader;

void gradientBandWeights(std::span<const glm::vec2> points, glm::vec2 p, std::span<float> weights) {
  float sum = 0.0f;
  for (size_t i = 0; i < points.size(); ++i) {
    float h = 1.0f;
    for (size_t j = 0; j < points.size() && h > 0.0f; ++j) {
      if (j == i) continue;
      const glm::vec2 edge = points[j] - points[i];
      h = std::min(h, std::clamp(1.0f - glm::dot(p - points[i], edge) / glm::dot(edge, edge), 0.0f, 1.0f));
    }
    weights[i] = h;
    sum += h;
  }
  if (sum > 1e-6f) {
    for (float& w : weights) w /= sum;
    return;
  }
  // Every band is empty only far outside all poles: fall back to the nearest.
  size_t nearest = 0;
  for (size_t i = 1; i < points.size(); ++i)
    if (glm::distance(p, points[i]) < glm::distance(p, points[nearest])) nearest = i;
  std::fill(weights.begin(), weights.end(), 0.0f);
  weights[nearest] = 1.0f;
}

void FreeformMapNode::weightsAt(glm::vec2 cursor, std::span<float> weights) const {
  if (!std::isfinite(cursor.x) || !std::isfinite(cursor.y)) cursor = glm::vec2(0.0f);
  const float length = glm::length(cursor);
  if (length > radius) cursor *= radius / length;
  gradientBandWeights(points, cursor, weights);
}

void FreeformMapNode::inputs(std::vector<NodeIndex>& out) const {
  out.push_back(neutral);
  for (const FreeformPole& pole : poles) out.push_back(pole.node);
}

eng::Result<void> FreeformMapNode::prepare(const BuildContext& ctx) {
  if (poles.empty() || poles.size() > kMaxFreeformPoles)
    return ctx.problem("poles", "needs 1 to " + std::to_string(kMaxFreeformPoles) + " poles, got " +
                                    std::to_string(poles.size()));
  points = {glm::vec2(0.0f)};
  nodes = {neutral};
  radius = 0.0f;
  for (size_t i = 0; i < poles.size(); ++i) {
    const glm::vec2 at = poles[i].position;
    const std::string where = "poles/" + std::to_string(i) + "/at";
    if (!std::isfinite(at.x) || !std::isfinite(at.y)) return ctx.problem(where, "position is not finite");
    for (size_t j = 0; j < points.size(); ++j)
      if (glm::distance(at, points[j]) < 1e-3f)
        return ctx.problem(where, j == 0 ? std::string("pole lies on neutral at the centre (0,0)")
                                         : "pole lies on pole " + std::to_string(j - 1));
    points.push_back(at);
    nodes.push_back(poles[i].node);
    radius = std::max(radius, glm::length(at));
  }
  if (auto p = ctx.checkInput(x, "x"); !p) return p;
  return ctx.checkInput(y, "y");
}

void FreeformMapNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  std::array<float, kMaxFreeformPoles + 1> storage;
  const std::span<float> weights(storage.data(), points.size());
  weightsAt({ctx.read(x), ctx.read(y)}, weights);
  ctx.evaluateWeightedSum(nodes, weights, out);
}

eng::Result<FreeformMapNode> FreeformMapNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "neutral", "poles", "x", "y"}));
  FreeformMapNode m;
  m.neutral = ENG_TRY_VALUE(r.nodeAt(j, "neutral"));
  const JsonNode poles = ENG_TRY_VALUE(j.at("poles"));
  const size_t count = ENG_TRY_VALUE(poles.size());
  for (size_t i = 0; i < count; ++i) {
    const JsonNode p = poles.element(i);
    ENG_TRY(p.allowOnly({"at", "node"}));
    const JsonNode at = ENG_TRY_VALUE(p.at("at"));
    if (ENG_TRY_VALUE(at.size()) != 2) return at.error("expected [x, y]");
    const float x = ENG_TRY_VALUE(at.element(0).number());
    const float y = ENG_TRY_VALUE(at.element(1).number());
    m.poles.push_back({{x, y}, ENG_TRY_VALUE(r.nodeAt(p, "node"))});
  }
  m.x = ENG_TRY_VALUE(r.floatInput(j, "x", 0.0f));
  m.y = ENG_TRY_VALUE(r.floatInput(j, "y", 0.0f));
  return m;
}

}  // namespace facial
