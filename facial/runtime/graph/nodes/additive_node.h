#pragma once
// Additive action-unit layer: speech, a blink or a gesture riding on top of
// an emotion. Per channel c:
//   out[c] = clamp(base[c] + weight * mask[c] * layer[c], 0, 1)
// The mask selects channels by face region and side (action_units.h): a
// channel passes when it matches both the region (any / upper / lower) and
// the side (any / left / right / both = bilateral channels only). Channels of
// unknown region (raw target names) pass only a region of "any". Lanes come
// from the base: the layer does not change what the emotion asks of blinking.
//
// JSON (graph_json.h): "additive": base, layer, weight, mask {"region": any|upper|lower, "side": any|left|right|both}
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/graph/channel_set.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

struct RegionMask {
  std::optional<FaceRegion> region;  // nullopt: any region
  std::optional<FaceSide> side;      // nullopt: any side

  // 1 when the channel passes, else 0.
  float weight(const ChannelInfo& channel) const;
};

struct AdditiveNode {
  static constexpr std::string_view kType = "additive";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<AdditiveNode> read(const JsonNode& j, detail::NodeReader& r);

  NodeIndex base = kNoNode;
  NodeIndex layer = kNoNode;
  FloatInput weight = FloatInput::fixed(1.0f);
  RegionMask mask;

  std::vector<float> maskWeights;  // derived at build: one per channel

  static constexpr uint32_t kScratchPoses = 1;
  void inputs(std::vector<NodeIndex>& out) const { out.insert(out.end(), {base, layer}); }
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
