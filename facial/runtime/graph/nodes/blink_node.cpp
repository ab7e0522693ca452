#include "facial/runtime/graph/nodes/blink_node.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace facial {

using detail::NodeReader;
namespace {

float cosineEase(float s) { return 0.5f * (1.0f - std::cos(std::numbers::pi_v<float> * std::clamp(s, 0.0f, 1.0f))); }

// Uniform in [0,1) from the standard-defined minstd_rand sequence (the
// <random> distributions differ between standard libraries; this does not).
float uniform01(std::minstd_rand& rng) {
  return static_cast<float>(rng() - std::minstd_rand::min()) /
         static_cast<float>(std::minstd_rand::max() - std::minstd_rand::min() + 1);
}

// SplitMix64 finaliser: spreads (seed, node) over the generator's seed space.
uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

float BlinkNode::curve(Phase phase, float phaseTime) const {
  switch (phase) {
    case Phase::Open: return 0.0f;
    case Phase::Closing: return cosineEase(phaseTime / closeDuration);
    case Phase::Closed: return 1.0f;
    case Phase::Opening: return 1.0f - cosineEase(phaseTime / openDuration);
  }
  return 0.0f;
}

float BlinkNode::maxRate() const {
  return std::numbers::pi_v<float> / 2.0f / std::min(closeDuration, openDuration);
}

eng::Result<void> BlinkNode::prepare(const BuildContext& ctx) {
  auto resolve = [&](const std::vector<std::string>& names, std::vector<uint32_t>& indices,
                     const char* field) -> eng::Result<void> {
    indices.clear();
    for (size_t i = 0; i < names.size(); ++i) {
      auto c = ctx.channels.find(names[i]);
      if (!c)
        return ctx.problem(std::string(field) + "/" + std::to_string(i),
                           "'" + names[i] + "' is not a channel of this graph");
      indices.push_back(*c);
    }
    return {};
  };
  if (auto p = resolve(channels, channelIndices, "channels"); !p) return p;
  if (auto p = resolve(wideChannels, wideIndices, "wideChannels"); !p) return p;
  if (channels.empty())
    for (uint32_t c = 0; c < ctx.channels.size(); ++c)
      if (auto au = actionUnitIndex(ctx.channels[c].name); au && actionUnits()[*au].facsNumber == 45)
        channelIndices.push_back(c);
  if (wideChannels.empty())
    for (uint32_t c = 0; c < ctx.channels.size(); ++c)
      if (auto au = actionUnitIndex(ctx.channels[c].name); au && actionUnits()[*au].facsNumber == 5)
        wideIndices.push_back(c);
  if (channelIndices.empty())
    return ctx.problem("channels", "no blink channels: the graph has no AU45 channel, name them in \"channels\"");
  struct Positive { const char* name; float value; };
  for (Positive p : {Positive{"minInterval", minInterval}, Positive{"maxInterval", maxInterval},
                     Positive{"closeDuration", closeDuration}, Positive{"openDuration", openDuration},
                     Positive{"doubleBlinkGap", doubleBlinkGap}})
    if (!std::isfinite(p.value) || p.value <= 0.0f)
      return ctx.problem(p.name, "must be a finite number > 0 (got " + formatNumber(p.value) + ")");
  if (maxInterval < minInterval)
    return ctx.problem("maxInterval", "is shorter than minInterval (" + formatNumber(maxInterval) + " < " +
                                          formatNumber(minInterval) + ")");
  if (!std::isfinite(closedDuration) || closedDuration < 0.0f)
    return ctx.problem("closedDuration", "must be a finite number >= 0");
  if (!std::isfinite(doubleBlinkChance) || doubleBlinkChance < 0.0f || doubleBlinkChance > 1.0f)
    return ctx.problem("doubleBlinkChance", "must lie in [0,1]");
  if (!std::isfinite(wideStart) || !std::isfinite(wideFull) || !(wideFull > wideStart))
    return ctx.problem("wideFull", "must be greater than wideStart");
  return ctx.checkInput(amount, "amount");
}

float BlinkNode::drawInterval(State& state) const {
  return minInterval + (maxInterval - minInterval) * uniform01(state.rng);
}

BlinkNode::State BlinkNode::makeState(const GraphDefinition&, NodeIndex self, uint64_t seed) const {
  State state;
  state.rng.seed(static_cast<std::minstd_rand::result_type>(mix(seed ^ mix(self)) % 2147483646u + 1u));
  reset(state);
  state.waitTime = drawInterval(state);
  return state;
}

void BlinkNode::reset(State&) const {
  // Blinking is independent of the states around it: re-entering a state
  // must not restart or cut a blink in progress.
}

void BlinkNode::advance(State& state, float dt, bool mayStart) const {
  state.phaseTime += dt;
  // A long frame may cross several phases; each pass consumes one.
  for (int guard = 0; guard < 8; ++guard) {
    float length = 0.0f;
    switch (state.phase) {
      case Phase::Open: length = state.waitTime; break;
      case Phase::Closing: length = closeDuration; break;
      case Phase::Closed: length = closedDuration; break;
      case Phase::Opening: length = openDuration; break;
    }
    if (state.phaseTime < length) return;
    if (state.phase == Phase::Open && !mayStart) {
      state.phaseTime = length;  // overdue: starts as soon as it is allowed
      return;
    }
    state.phaseTime -= length;
    switch (state.phase) {
      case Phase::Open: state.phase = Phase::Closing; break;
      case Phase::Closing: state.phase = Phase::Closed; break;
      case Phase::Closed: state.phase = Phase::Opening; break;
      case Phase::Opening:
        state.phase = Phase::Open;
        // A double blink: the second follows after a short gap, never a third.
        state.secondOfDouble = !state.secondOfDouble && uniform01(state.rng) < doubleBlinkChance;
        state.waitTime = state.secondOfDouble ? doubleBlinkGap : drawInterval(state);
        break;
    }
  }
}

void BlinkNode::evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const {
  State& state = ctx.state<State>(self);
  ctx.evaluate(input, out);
  const size_t channelCount = out.size() - kPoseLaneCount;
  const float block = std::clamp(out[channelCount + kLaneOverrideBlinkBlock], 0.0f, 1.0f);
  const float blend = std::clamp(out[channelCount + kLaneOverrideBlinkBlend], 0.0f, 1.0f);
  float wide = 0.0f;
  for (uint32_t c : wideIndices) wide = std::max(wide, out[c]);
  const float amplitude = std::clamp(ctx.read(amount), 0.0f, 1.0f) * (1.0f - glm::smoothstep(wideStart, wideFull, wide)) *
                          (1.0f - block) * (1.0f - blend);
  advance(state, ctx.dt, /*mayStart=*/block <= 0.0f && amplitude > 0.05f);
  const float b = curve(state.phase, state.phaseTime) * amplitude;
  for (uint32_t c : channelIndices) out[c] = out[c] + (1.0f - out[c]) * b;
}

eng::Result<BlinkNode> BlinkNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "input", "channels", "wideChannels", "amount", "minInterval", "maxInterval",
                       "closeDuration", "closedDuration", "openDuration", "doubleBlinkChance", "doubleBlinkGap",
                       "wideStart", "wideFull"}));
  BlinkNode b;
  b.input = ENG_TRY_VALUE(r.nodeAt(j, "input"));
  auto names = [&](std::string_view key) -> eng::Result<std::vector<std::string>> {
    std::vector<std::string> out;
    if (auto list = j.find(key)) {
      const size_t count = ENG_TRY_VALUE(list->size());
      for (size_t i = 0; i < count; ++i) out.push_back(ENG_TRY_VALUE(list->element(i).string()));
    }
    return out;
  };
  b.channels = ENG_TRY_VALUE(names("channels"));
  b.wideChannels = ENG_TRY_VALUE(names("wideChannels"));
  b.amount = ENG_TRY_VALUE(r.floatInput(j, "amount", 1.0f));
  for (auto [key, value] : {std::pair{"minInterval", &b.minInterval}, {"maxInterval", &b.maxInterval},
                            {"closeDuration", &b.closeDuration}, {"closedDuration", &b.closedDuration},
                            {"openDuration", &b.openDuration}, {"doubleBlinkChance", &b.doubleBlinkChance},
                            {"doubleBlinkGap", &b.doubleBlinkGap}, {"wideStart", &b.wideStart},
                            {"wideFull", &b.wideFull}})
    *value = ENG_TRY_VALUE(j.numberOr(key, *value));
  return b;
}

}  // namespace facial
