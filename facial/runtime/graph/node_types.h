#pragma once
// Vocabulary shared by the graph's node files: node indices and the pose
// layout. A pose is the rig channels followed by a few lanes, control values
// that blend like weights but never reach the mesh (the VRM blink override
// an expression asks for travels through blends and transitions this way).
//
// Every node type is a struct holding its immutable definition, with
//   void inputs(std::vector<NodeIndex>&) const;        children it pulls from
//   static constexpr uint32_t kScratchPoses;           temporaries it holds while children evaluate
//   eng::Result<void> prepare(const BuildContext&);       validation + derived data, at build
//   void evaluate(EvalContext&, NodeIndex self, std::span<float> out) const;  per frame
// and, when it keeps per-character state, a nested `State` with
//   State makeState(const GraphDefinition&, NodeIndex self, uint64_t seed) const;
//   void reset(State&) const;                            on (re-)entering its state
#include <cstdint>
#include <limits>

#include "engine/core/result.h"  // prepare()'s result

namespace facial {

using NodeIndex = uint32_t;
inline constexpr NodeIndex kNoNode = std::numeric_limits<NodeIndex>::max();

// Lane offsets after the channels: pose[channelCount + lane].
enum PoseLane : uint32_t {
  kLaneOverrideBlinkBlock = 0,  // 1 where an expression blocks blinking
  kLaneOverrideBlinkBlend = 1,  // 1 where an expression scales blinking down by its weight
  kPoseLaneCount = 2,
};

struct EvalContext;     // nodes/eval_context.h
struct BuildContext;    // nodes/build_context.h
class GraphDefinition;  // graph_definition.h

}  // namespace facial
