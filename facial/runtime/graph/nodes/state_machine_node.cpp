#include "facial/runtime/graph/nodes/state_machine_node.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/graph/pose_jobs.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

using detail::NodeReader;

std::string_view conditionOpName(ConditionOp value) { return eng::nameOf(kConditionOpNames, value); }

std::optional<ConditionOp> conditionOpFromName(std::string_view name) { return eng::valueNamed(kConditionOpNames, name); }

bool TransitionCondition::holds(std::span<const float> parameters) const {
  const float v = parameters[parameter];
  switch (op) {
    case ConditionOp::Greater: return v > threshold;
    case ConditionOp::GreaterEqual: return v >= threshold;
    case ConditionOp::Less: return v < threshold;
    case ConditionOp::LessEqual: return v <= threshold;
    case ConditionOp::Equal: return v == threshold;
    case ConditionOp::NotEqual: return v != threshold;
    case ConditionOp::IsTrue:
    case ConditionOp::Triggered: return v != 0.0f;
    case ConditionOp::IsFalse: return v == 0.0f;
  }
  return false;
}

std::optional<uint32_t> StateMachineNode::findState(std::string_view name) const { return stateIndex.find(name); }

StateMachineStatus StateMachineNode::status(const State& state) const {
  StateMachineStatus s;
  s.current = state.current;
  if (state.blending && state.liveSource != State::kNone) s.liveSource = state.liveSource;
  s.blending = state.blending;
  s.fromSnapshot = state.blending && state.liveSource == State::kNone;
  s.blendProgress = state.blending ? std::min(1.0f, state.blendTime / state.transition->duration) : 1.0f;
  s.stateTime = state.stateTime;
  return s;
}

void StateMachineNode::inputs(std::vector<NodeIndex>& out) const {
  for (const MachineState& s : states) out.push_back(s.node);
}

namespace {

eng::Result<void> prepareTransitions(const BuildContext& ctx, const StateMachineNode& machine,
                                     std::vector<Transition>& transitions, const std::string& path, bool anyState) {
  for (size_t i = 0; i < transitions.size(); ++i) {
    Transition& t = transitions[i];
    const std::string where = path + "/" + std::to_string(i);
    auto target = machine.findState(t.to);
    if (!target) return ctx.problem(where + "/to", "no state named '" + t.to + "'");
    t.target = *target;
    if (!std::isfinite(t.duration) || t.duration <= 0.0f)
      return ctx.problem(where + "/duration",
                         "must be a finite number > 0 (got " + formatNumber(t.duration) +
                             "); a cut would make the face jump");
    if (!(t.curve.maxSlope() < INFINITY))
      return ctx.problem(where + "/curve", "the curve jumps (step key or vertical bezier end): the face would pop");
    if (t.exitTime && (!std::isfinite(*t.exitTime) || *t.exitTime < 0.0f))
      return ctx.problem(where + "/exitTime", "must be a finite number >= 0 (got " + formatNumber(*t.exitTime) + ")");
    if (t.conditions.empty() && !t.exitTime)
      return ctx.problem(where, "has neither conditions nor an exit time, so it would fire at once, every frame");
    if (t.canTransitionToSelf && !anyState)
      return ctx.problem(where + "/canTransitionToSelf", "only any-state transitions take this flag");
    for (size_t c = 0; c < t.conditions.size(); ++c) {
      const TransitionCondition& cond = t.conditions[c];
      const std::string field = where + "/conditions/" + std::to_string(c) + "/parameter";
      const ParameterType needed = cond.op == ConditionOp::Triggered ? ParameterType::Trigger
                                   : (cond.op == ConditionOp::IsTrue || cond.op == ConditionOp::IsFalse)
                                       ? ParameterType::Bool
                                       : ParameterType::Float;
      if (auto p = ctx.checkParameter(cond.parameter, needed, field); !p) return p;
      if (!std::isfinite(cond.threshold))
        return ctx.problem(where + "/conditions/" + std::to_string(c) + "/value", "is not finite");
    }
  }
  std::stable_sort(transitions.begin(), transitions.end(),
                   [](const Transition& a, const Transition& b) { return a.priority > b.priority; });
  return {};
}

}  // namespace

eng::Result<void> StateMachineNode::prepare(const BuildContext& ctx) {
  if (states.empty()) return ctx.problem("states", "a state machine needs at least one state");
  stateIndex = {};
  stateIndex.reserve(states.size());
  for (size_t i = 0; i < states.size(); ++i) {
    if (states[i].name.empty()) return ctx.problem("states/" + std::to_string(i) + "/name", "empty state name");
    if (!stateIndex.add(states[i].name, static_cast<uint32_t>(i)))
      return ctx.problem("states/" + std::to_string(i) + "/name", "state '" + states[i].name + "' is declared twice");
  }
  if (defaultState.empty()) {
    defaultIndex = 0;
  } else if (auto d = findState(defaultState)) {
    defaultIndex = *d;
  } else {
    return ctx.problem("defaultState", "no state named '" + defaultState + "'");
  }
  for (size_t i = 0; i < states.size(); ++i)
    if (auto p = prepareTransitions(ctx, *this, states[i].transitions, "states/" + std::to_string(i) + "/transitions",
                                    false);
        !p)
      return p;
  return prepareTransitions(ctx, *this, anyState, "anyState", true);
}

StateMachineNode::State StateMachineNode::makeState(const GraphDefinition& definition, NodeIndex, uint64_t) const {
  State state;
  state.snapshot.assign(definition.poseStride(), 0.0f);
  state.lastOutput.assign(definition.poseStride(), 0.0f);
  reset(state);
  return state;
}

void StateMachineNode::reset(State& state) const {
  state.current = defaultIndex;
  state.liveSource = State::kNone;
  state.stateTime = 0.0f;
  state.blending = false;
  state.blendTime = 0.0f;
  state.transition = nullptr;
  state.hasOutput = false;
}

const Transition* StateMachineNode::choose(const State& state, std::span<const float> parameters) const {
  auto fires = [&](const Transition& t) {
    if (t.exitTime && state.stateTime < *t.exitTime) return false;
    for (const TransitionCondition& c : t.conditions)
      if (!c.holds(parameters)) return false;
    return true;
  };
  // Both lists are sorted by priority; on a tie the any-state transition wins.
  const Transition* best = nullptr;
  for (const Transition& t : anyState) {
    if (t.target == state.current && !t.canTransitionToSelf) continue;
    if (fires(t)) {
      best = &t;
      break;
    }
  }
  for (const Transition& t : states[state.current].transitions) {
    if (best && t.priority <= best->priority) break;
    if (fires(t)) return &t;
  }
  return best;
}

void StateMachineNode::begin(EvalContext& ctx, State& state, const Transition& transition) const {
  // A transition whose exit time was crossed during this step really began
  // at the exit time: the new state starts with the part of the step past
  // it, so timing does not drift by up to one step per state with the frame
  // rate (a 2.4 s exit at 4 fps would otherwise last 2.5 s).
  float carried = 0.0f;
  if (transition.exitTime) {
    const float past = state.stateTime - *transition.exitTime;
    if (past > 0.0f && past < ctx.dt) carried = past;
  }
  for (const TransitionCondition& c : transition.conditions)
    if (c.op == ConditionOp::Triggered) ctx.parameters[c.parameter] = 0.0f;
  if (!state.hasOutput) {
    // Nothing has been shown yet: start in the destination, nothing to blend from.
    state.blending = false;
    state.liveSource = State::kNone;
  } else if (state.blending || transition.target == state.current) {
    // Interrupting (or re-entering): blend from exactly what is on screen,
    // i.e. last frame's weights as displayed, in [0,1]. (An overshooting
    // curve may have pushed them outside; starting from the unclamped value
    // would make the face hold still, then jump by the overshoot.)
    for (size_t i = 0; i < state.snapshot.size(); ++i) state.snapshot[i] = std::clamp(state.lastOutput[i], 0.0f, 1.0f);
    state.liveSource = State::kNone;
    state.blending = true;
  } else {
    state.liveSource = state.current;
    state.blending = true;
  }
  state.current = transition.target;
  state.stateTime = carried;
  state.blendTime = carried;
  state.transition = state.blending ? &transition : nullptr;
  ctx.reset(states[transition.target].node);
}

void StateMachineNode::evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const {
  State& state = ctx.state<State>(self);
  state.stateTime += ctx.dt;
  if (state.blending) {
    state.blendTime += ctx.dt;
    if (state.blendTime >= state.transition->duration) {
      state.blending = false;
      state.liveSource = State::kNone;
      state.transition = nullptr;
    }
  }
  if (!state.blending || state.transition->interruptible)
    if (const Transition* t = choose(state, ctx.parameters)) begin(ctx, state, *t);

  ctx.evaluate(states[state.current].node, out);
  if (state.blending) {
    const float w = state.transition->curve(state.blendTime / state.transition->duration);
    if (state.liveSource != State::kNone) {
      ScratchPose source(ctx.scratch);
      ctx.evaluate(states[state.liveSource].node, source.pose());
      LerpPoseJob{.a = source.pose(), .b = out, .t = w, .out = out}.Run();
    } else {
      LerpPoseJob{.a = state.snapshot, .b = out, .t = w, .out = out}.Run();
    }
  }
  std::copy(out.begin(), out.end(), state.lastOutput.begin());
  state.hasOutput = true;
}

namespace {

eng::Result<TransitionCondition> readCondition(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"parameter", "op", "value"}));
  TransitionCondition c;
  c.parameter = ENG_TRY_VALUE(r.parameter(ENG_TRY_VALUE(j.at("parameter"))));
  switch (r.parameterType(c.parameter)) {
    case ParameterType::Trigger:
      if (j.has("op") || j.has("value")) return j.error("a trigger condition takes only \"parameter\"");
      c.op = ConditionOp::Triggered;
      break;
    case ParameterType::Bool:
      if (j.has("op")) return ENG_TRY_VALUE(j.at("op")).error("a bool condition takes \"value\": true or false");
      c.op = ENG_TRY_VALUE(j.booleanOr("value", true)) ? ConditionOp::IsTrue : ConditionOp::IsFalse;
      break;
    case ParameterType::Float: {
      const JsonNode op = ENG_TRY_VALUE(j.at("op"));
      const std::string name = ENG_TRY_VALUE(op.string());
      auto parsed = conditionOpFromName(name);
      if (!parsed || *parsed == ConditionOp::IsTrue || *parsed == ConditionOp::IsFalse ||
          *parsed == ConditionOp::Triggered)
        return op.error("unknown comparison '" + name + "' (expected >, >=, <, <=, == or !=)");
      c.op = *parsed;
      c.threshold = ENG_TRY_VALUE(j.numberAt("value"));
      break;
    }
  }
  return c;
}

eng::Result<Transition> readTransition(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"to", "duration", "curve", "exitTime", "priority", "interruptible", "canTransitionToSelf",
                       "conditions"}));
  Transition t;
  t.to = ENG_TRY_VALUE(j.stringAt("to"));
  t.duration = ENG_TRY_VALUE(j.numberOr("duration", t.duration));
  t.curve = ENG_TRY_VALUE(r.curve(j));
  if (auto e = j.find("exitTime")) t.exitTime = ENG_TRY_VALUE(e->number());
  if (auto p = j.find("priority")) {
    if (!p->raw().is_number_integer()) return p->error("expected an integer, got " + p->raw().dump());
    t.priority = p->raw().get<int>();
  }
  t.interruptible = ENG_TRY_VALUE(j.booleanOr("interruptible", true));
  t.canTransitionToSelf = ENG_TRY_VALUE(j.booleanOr("canTransitionToSelf", false));
  if (auto conditions = j.find("conditions")) {
    const size_t count = ENG_TRY_VALUE(conditions->size());
    for (size_t c = 0; c < count; ++c) t.conditions.push_back(ENG_TRY_VALUE(readCondition(conditions->element(c), r)));
  }
  return t;
}

eng::Result<std::vector<Transition>> readTransitions(const JsonNode& list, NodeReader& r) {
  const size_t count = ENG_TRY_VALUE(list.size());
  std::vector<Transition> out;
  for (size_t i = 0; i < count; ++i) out.push_back(ENG_TRY_VALUE(readTransition(list.element(i), r)));
  return out;
}

}  // namespace

eng::Result<StateMachineNode> StateMachineNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "states", "anyState", "defaultState"}));
  StateMachineNode m;
  const JsonNode states = ENG_TRY_VALUE(j.at("states"));
  const size_t count = ENG_TRY_VALUE(states.size());
  for (size_t i = 0; i < count; ++i) {
    const JsonNode s = states.element(i);
    ENG_TRY(s.allowOnly({"name", "node", "transitions"}));
    MachineState state;  // one read per statement: ENG_TRY_VALUE must not leave a half-built aggregate (result.h)
    state.name = ENG_TRY_VALUE(s.stringAt("name"));
    state.node = ENG_TRY_VALUE(r.nodeAt(s, "node"));
    if (auto t = s.find("transitions")) state.transitions = ENG_TRY_VALUE(readTransitions(*t, r));
    m.states.push_back(std::move(state));
  }
  if (auto any = j.find("anyState")) m.anyState = ENG_TRY_VALUE(readTransitions(*any, r));
  m.defaultState = ENG_TRY_VALUE(j.stringOr("defaultState", ""));
  return m;
}

}  // namespace facial
