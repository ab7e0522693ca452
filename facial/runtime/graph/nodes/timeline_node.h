#pragma once
// Timeline clip node: plays one of the graph's timelines over the channels
// its tracks name (other channels read 0). Playback time advances by
// speed * dt (negative plays backward) and maps into the clip by the loop
// mode; each track keeps a cursor so forward playback is O(1) amortised.
//
// JSON (graph_json.h): "timeline": timeline (name), loop once|clamp|loop|pingpong, speed
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/graph/timeline.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

struct TimelineNode {
  static constexpr std::string_view kType = "timeline";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<TimelineNode> read(const JsonNode& j, detail::NodeReader& r);

  uint32_t timeline = 0;          // index into the graph's timelines
  std::optional<LoopMode> loop;   // overrides the timeline's own loop mode
  FloatInput speed = FloatInput::fixed(1.0f);

  // Derived at build.
  std::vector<uint32_t> trackChannels;  // channel index per track
  LoopMode loopMode = LoopMode::Once;
  float duration = 1;

  struct State {
    float time = 0;  // playback time, kept inside one period so it never loses precision
    std::vector<uint32_t> cursors;
  };

  static constexpr uint32_t kScratchPoses = 0;
  void inputs(std::vector<NodeIndex>&) const {}
  eng::Result<void> prepare(const BuildContext& ctx);
  State makeState(const GraphDefinition& definition, NodeIndex self, uint64_t seed) const;
  void reset(State& state) const;
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
