#pragma once
// State machine node (Mecanim style). Each state holds a node; transitions
// carry a duration, an easing curve, conditions on parameters (float
// compares, bools, triggers that are consumed when the transition fires), an
// optional exit time, a priority, and may start from any state.
//
// Blending: out = (1 - c(tau / duration)) source + c(tau / duration) destination.
// An uninterrupted transition blends from the source state evaluated live.
// A transition that interrupts one in flight (or re-enters the current
// state) snapshots the pose that was on screen last frame (clamped to [0,1]
// like the displayed weights) and blends from that frozen snapshot, so whatever sequence of triggers arrives the output
// never jumps: per frame it moves at most maxSlope(c) * dt / duration times
// the distance between source and destination, plus what the destination's
// own animation moves.
//
// JSON (graph_json.h): "stateMachine": states [{name, node, transitions}], anyState [transitions], defaultState
//     transition: to, duration, curve, exitTime, priority, interruptible, canTransitionToSelf,
//                 conditions [{"parameter": p, "op": ">"|">="|"<"|"<="|"=="|"!=", "value": v}
//                             | {"parameter": bool, "value": true} | {"parameter": trigger}]
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/core/name_index.h"
#include "engine/core/result.h"
#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

enum class ConditionOp : uint8_t { Greater, GreaterEqual, Less, LessEqual, Equal, NotEqual, IsTrue, IsFalse, Triggered };
inline constexpr eng::EnumName<ConditionOp> kConditionOpNames[] = {
    {ConditionOp::Greater, ">"},
    {ConditionOp::GreaterEqual, ">="},
    {ConditionOp::Less, "<"},
    {ConditionOp::LessEqual, "<="},
    {ConditionOp::Equal, "=="},
    {ConditionOp::NotEqual, "!="},
    {ConditionOp::IsTrue, "true"},
    {ConditionOp::IsFalse, "false"},
    {ConditionOp::Triggered, "triggered"},
};
std::string_view conditionOpName(ConditionOp value);
std::optional<ConditionOp> conditionOpFromName(std::string_view name);

struct TransitionCondition {
  ParameterIndex parameter = kNoParameter;
  ConditionOp op = ConditionOp::Triggered;  // compares need a float, IsTrue/IsFalse a bool, Triggered a trigger
  float threshold = 0;

  bool holds(std::span<const float> parameters) const;
};

struct Transition {
  std::string to;                        // destination state's name
  float duration = 0.25f;                // seconds, > 0
  EasingCurve curve;                     // linear by default
  std::optional<float> exitTime;         // seconds the source state must have run
  int priority = 0;                      // higher is checked first
  bool interruptible = true;             // may another transition cut in while this one blends
  bool canTransitionToSelf = false;      // any-state transitions only
  std::vector<TransitionCondition> conditions;  // all must hold
  uint32_t target = 0;                   // derived at build from `to`
};

struct MachineState {
  std::string name;
  NodeIndex node = kNoNode;
  std::vector<Transition> transitions;
};

// Where one instance's state machine stands (for tools, tests, UI).
struct StateMachineStatus {
  uint32_t current = 0;                  // the active state (destination while blending)
  std::optional<uint32_t> liveSource;    // state blended from, when not a snapshot
  bool blending = false;
  bool fromSnapshot = false;             // blending from a frozen snapshot (after an interruption)
  float blendProgress = 1;               // tau / duration in [0,1]
  float stateTime = 0;                   // seconds in `current`
};

struct StateMachineNode {
  static constexpr std::string_view kType = "stateMachine";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<StateMachineNode> read(const JsonNode& j, detail::NodeReader& r);

  std::vector<MachineState> states;
  std::vector<Transition> anyState;
  std::string defaultState;  // empty: the first state

  uint32_t defaultIndex = 0;  // derived at build
  eng::NameIndex stateIndex;  // derived at build: state names to indices

  struct State {
    static constexpr uint32_t kNone = UINT32_MAX;
    uint32_t current = 0;
    uint32_t liveSource = kNone;
    float stateTime = 0;
    bool blending = false;
    float blendTime = 0;
    const Transition* transition = nullptr;  // the one blending (points into the shared definition)
    bool hasOutput = false;                  // lastOutput holds a frame
    std::vector<float> snapshot;             // frozen source after an interruption
    std::vector<float> lastOutput;           // what was on screen last frame
  };

  // After prepare(), which indexes the names.
  std::optional<uint32_t> findState(std::string_view name) const;
  StateMachineStatus status(const State& state) const;

  static constexpr uint32_t kScratchPoses = 1;
  void inputs(std::vector<NodeIndex>& out) const;
  // Validates, resolves names, and orders each transition list by priority
  // (stable: equal priorities keep declaration order).
  eng::Result<void> prepare(const BuildContext& ctx);
  State makeState(const GraphDefinition& definition, NodeIndex self, uint64_t seed) const;
  void reset(State& state) const;
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;

 private:
  const Transition* choose(const State& state, std::span<const float> parameters) const;
  void begin(EvalContext& ctx, State& state, const Transition& transition) const;
};

}  // namespace facial
