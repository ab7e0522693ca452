// Animation graph update cost: one frame of a representative character graph
// (procedural blink over an additive speech layer over a 7-state emotion
// state machine that is always transitioning), against the number of
// channels (21 action units, 52 ARKit-sized, 256) and the number of
// characters sharing one definition (1, 100, 1000).
//   build/bin/facial_bench --benchmark_filter=Graph
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/graph_instance.h"
#include "tests/common/allocation_counter.h"

namespace {

using namespace facial;

constexpr float kFrame = 1.0f / 60.0f;

ChannelSet channelsOfSize(int count) {
  if (count == static_cast<int>(actionUnits().size())) return ChannelSet::actionUnits();
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.push_back("target" + std::to_string(i));
  return ChannelSet::fromNames(names).value();
}

// blink(additive(stateMachine(7 poses, A -> B -> ... -> A every 0.5 s, 0.4 s cosine blends), talk timeline)).
SharedGraphDefinition characterGraph(int channelCount) {
  GraphBuilder b(channelsOfSize(channelCount));
  const uint32_t n = b.channels().size();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  StateMachineNode machine;
  for (int s = 0; s < 7; ++s) {
    std::vector<float> pose(n);
    for (float& w : pose) w = weight(rng) < 0.3f ? weight(rng) : 0.0f;
    machine.states.push_back({"s" + std::to_string(s), b.add(PoseNode{.weights = pose}), {}});
  }
  for (int s = 0; s < 7; ++s)
    machine.states[s].transitions.push_back(
        {.to = "s" + std::to_string((s + 1) % 7), .duration = 0.4f, .curve = EasingCurve::cosine(), .exitTime = 0.5f});
  Timeline talk;
  talk.name = "talk";
  talk.duration = 1.2f;
  talk.loop = LoopMode::Loop;
  for (uint32_t c = 0; c < n; c += 8) {
    std::vector<Keyframe> keys;
    for (int k = 0; k <= 12; ++k) keys.push_back({0.1f * k, (k % 3) * 0.3f, 0, 0, KeyInterpolation::Cosine});
    talk.addTrack(b.channels()[c].name, keys);
  }
  const uint32_t clip = b.addTimeline(std::move(talk));
  const NodeIndex emotions = b.add(std::move(machine));
  const NodeIndex speech = b.add(TimelineNode{.timeline = clip});
  const NodeIndex layered = b.add(AdditiveNode{.base = emotions, .layer = speech, .weight = FloatInput::fixed(0.5f)});
  BlinkNode blink{.input = layered};
  if (b.channels().size() != actionUnits().size()) blink.channels = {"target0", "target1"};
  b.setRoot(b.add(std::move(blink)));
  return b.build().value();
}

void GraphUpdateChannels(benchmark::State& state) {
  const SharedGraphDefinition graph = characterGraph(static_cast<int>(state.range(0)));
  GraphInstance face = GraphInstance::create(graph, 1).value();
  for (auto _ : state) {
    face.update(kFrame);
    benchmark::DoNotOptimize(face.weights().data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["channels"] = static_cast<double>(graph->channelCount());
}
BENCHMARK(GraphUpdateChannels)->Arg(21)->Arg(52)->Arg(256);

void GraphUpdateCharacters(benchmark::State& state) {
  const SharedGraphDefinition graph = characterGraph(52);
  std::vector<GraphInstance> faces;
  for (int64_t i = 0; i < state.range(0); ++i) faces.push_back(GraphInstance::create(graph, static_cast<uint64_t>(i)).value());
  for (auto _ : state) {
    for (GraphInstance& face : faces) face.update(kFrame);
    benchmark::DoNotOptimize(faces.back().weights().data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));  // items = character updates
}
BENCHMARK(GraphUpdateCharacters)->Arg(1)->Arg(100)->Arg(1000);

// The sweep: 60 channels, 1 to 10,000 characters, each graph's state
// machine mid-transition (transitions every 0.5 s last 0.4 s, and every
// character starts at its own phase). Reports ns per character update
// (items_per_second inverted), allocations per update (must be 0: the update
// path reuses its buffers) and the heap bytes one character's GraphInstance holds.
void GraphUpdate60Channels(benchmark::State& state) {
  const SharedGraphDefinition graph = characterGraph(60);
  const int64_t count = state.range(0);
  const uint64_t bytesBefore = testing_support::allocatedBytes();
  std::vector<GraphInstance> faces;
  faces.reserve(size_t(count));
  for (int64_t i = 0; i < count; ++i) faces.push_back(GraphInstance::create(graph, static_cast<uint64_t>(i)).value());
  const double bytesPerCharacter = double(testing_support::allocatedBytes() - bytesBefore) / double(count);
  for (int64_t i = 0; i < count; ++i) faces[size_t(i)].update(0.05f + 0.4f * float(i % 7) / 7.0f);  // own phase
  const uint64_t allocationsBefore = testing_support::allocationCount();
  for (auto _ : state) {
    for (GraphInstance& face : faces) face.update(kFrame);
    benchmark::DoNotOptimize(faces.back().weights().data());
  }
  const uint64_t allocations = testing_support::allocationCount() - allocationsBefore;
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["characters"] = double(count);
  state.counters["channels"] = double(graph->channelCount());
  state.counters["ns_per_character"] =
      benchmark::Counter(double(count) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["allocs_per_update"] = double(allocations) / double(state.iterations() * count);
  state.counters["instance_bytes"] = bytesPerCharacter;
}
BENCHMARK(GraphUpdate60Channels)->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000);

}  // namespace
