#pragma once
// Pose node: a constant weight vector, typically an expression preset at an
// intensity (resolved when the graph is built, see preset_lookup.h) or
// explicit weights, optionally scaled at run time by a parameter.
//
// JSON (graph_json.h): "pose": preset + intensity | weights ({"channel": w} or [w, ...]); scale; overrideBlink none|block|blend
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/enum_names.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/rig/vrm_expressions.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

// JSON names of VRM overrides: "none", "block", "blend".
inline constexpr eng::EnumName<VrmOverride> kVrmOverrideNames[] = {
    {VrmOverride::None, "none"},
    {VrmOverride::Block, "block"},
    {VrmOverride::Blend, "blend"},
};
std::string_view vrmOverrideName(VrmOverride value);
std::optional<VrmOverride> vrmOverrideFromName(std::string_view name);

struct PoseNode {
  static constexpr std::string_view kType = "pose";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<PoseNode> read(const JsonNode& j, detail::NodeReader& r);

  std::vector<float> weights;                  // one per channel, each in [0,1]
  FloatInput scale = FloatInput::fixed(1.0f);  // multiplies weights and the override lane
  // VRM 1.0 overrideBlink: what this expression does to procedural blinking
  // while it shows, weighted by how much it shows (see blink_node.h).
  VrmOverride overrideBlink = VrmOverride::None;

  static constexpr uint32_t kScratchPoses = 0;
  void inputs(std::vector<NodeIndex>&) const {}
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
