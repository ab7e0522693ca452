#include "facial/runtime/graph/nodes/timeline_node.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"

namespace facial {

using detail::NodeReader;

eng::Result<void> TimelineNode::prepare(const BuildContext& ctx) {
  if (timeline >= ctx.timelines.size())
    return ctx.problem("timeline", "timeline index " + std::to_string(timeline) + " out of range (" +
                                       std::to_string(ctx.timelines.size()) + " timelines)");
  const Timeline& clip = ctx.timelines[timeline];
  if (auto valid = clip.validate(); !valid)
    return ctx.problem("timeline", "timeline '" + clip.name + "': " + valid.error().message);
  trackChannels.clear();
  for (const TimelineTrack& track : clip.tracks) {
    auto channel = ctx.channels.find(track.channel);
    if (!channel)
      return ctx.problem("timeline", "timeline '" + clip.name + "' animates '" + track.channel +
                                         "', which is not a channel of this graph");
    trackChannels.push_back(*channel);
  }
  loopMode = loop.value_or(clip.loop);
  duration = clip.duration;
  return ctx.checkInput(speed, "speed");
}

TimelineNode::State TimelineNode::makeState(const GraphDefinition&, NodeIndex, uint64_t) const {
  State state;
  state.cursors.assign(trackChannels.size(), 0);
  return state;
}

void TimelineNode::reset(State& state) const {
  state.time = 0.0f;
  std::fill(state.cursors.begin(), state.cursors.end(), 0u);
}

void TimelineNode::evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const {
  State& state = ctx.state<State>(self);
  state.time += ctx.read(speed) * ctx.dt;
  if (!std::isfinite(state.time)) state.time = 0.0f;  // an absurd speed parameter must not poison the clip
  // Keep the playback time within one period: same clip time, no float drift over hours.
  const float period = loopMode == LoopMode::PingPong ? 2.0f * duration : duration;
  if (loopMode == LoopMode::Once) state.time = std::clamp(state.time, 0.0f, duration);
  else if (state.time >= period || state.time < 0.0f) state.time -= period * std::floor(state.time / period);
  std::fill(out.begin(), out.end(), 0.0f);
  TimelineSampleJob{.timeline = &ctx.definition.timelines()[timeline],
                    .trackChannels = trackChannels,
                    .time = clipTime(loopMode, duration, state.time),
                    .cursors = state.cursors,
                    .out = out}
      .Run();
}

eng::Result<TimelineNode> TimelineNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "timeline", "loop", "speed"}));
  TimelineNode t;
  t.timeline = ENG_TRY_VALUE(r.timeline(ENG_TRY_VALUE(j.at("timeline"))));
  if (auto loop = j.find("loop")) {
    auto mode = loopModeFromName(ENG_TRY_VALUE(loop->string()));
    if (!mode) return loop->error("unknown loop mode (expected " + eng::nameList(kLoopModeNames) + ")");
    t.loop = *mode;
  }
  t.speed = ENG_TRY_VALUE(r.floatInput(j, "speed", 1.0f));
  return t;
}

}  // namespace facial
