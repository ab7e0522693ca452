#pragma once
// One character running a shared GraphDefinition: its parameter values, the
// state of its stateful nodes, preallocated scratch poses and its output.
// Everything is sized in create(); update() never allocates. Move-only.
//
//   auto face = GraphInstance::create(graph, /*seed=*/characterId);
//   const ParameterIndex happy = *graph->findParameter("happy");   // once
//   face->setTrigger(happy);                                       // any time
//   face->update(dt);                                              // per frame
//   upload(face->weights());                                       // channel weights in [0,1]
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/nodes/eval_context.h"

namespace facial {

class GraphInstance {
 public:
  // seed: the character's random stream (blink timing); same seed, same
  // parameters and same time steps give the same weights, bit for bit.
  static eng::Result<GraphInstance> create(SharedGraphDefinition definition, uint64_t seed = 0);

  // What one instance of `graph` holds (parameters, scratch and output poses,
  // every node's state): a crowd holds it once per character, so a caller
  // creating many charges count x this to its budget first.
  static size_t bytesFor(const GraphDefinition& graph);
  // The state one node adds to every instance, for a graph of `poseStride` floats per pose.
  static size_t nodeStateBytes(const NodeData& node, uint32_t poseStride);

  GraphInstance(GraphInstance&&) noexcept = default;
  GraphInstance& operator=(GraphInstance&&) noexcept = default;
  GraphInstance(const GraphInstance&) = delete;
  GraphInstance& operator=(const GraphInstance&) = delete;

  const GraphDefinition& definition() const { return *definition_; }

  // Advances by dt seconds and evaluates the graph. False (and no change)
  // when dt is negative or not finite.
  bool update(float dt);
  // The channel weights of the last update, each in [0,1] (zeros before the first).
  std::span<const float> weights() const { return std::span<const float>(output_).first(definition_->channelCount()); }
  // The whole last pose, lanes included (for tools).
  std::span<const float> pose() const { return output_; }

  // Parameter writes return false for an unknown index, the wrong type or a
  // non-finite value (the value is then left as it was).
  bool setFloat(ParameterIndex parameter, float value);
  bool setBool(ParameterIndex parameter, bool value);
  bool setTrigger(ParameterIndex parameter);    // stays set until a transition consumes it
  bool resetTrigger(ParameterIndex parameter);
  std::span<const float> parameters() const { return parameters_; }

  // Back to the state right after create() (parameters at their defaults;
  // the speech input is the host's and stays).
  void reset();

  // The speech the graph's speech nodes play from the next update() on: a
  // track (not owned; it must outlive its use, null: silence) sampled at the
  // host's audio-clock time. No allocation. False (no change) for a
  // non-finite time.
  bool setSpeech(const VisemeTrack* track, float audioTime);

  // Where a state machine node stands, or nullopt when `node` is not one.
  std::optional<StateMachineStatus> stateMachineStatus(NodeIndex node) const;

 private:
  GraphInstance() = default;
  bool setChecked(ParameterIndex parameter, ParameterType type, float value);

  SharedGraphDefinition definition_;
  uint64_t seed_ = 0;
  std::vector<float> parameters_;
  std::vector<NodeState> states_;
  ScratchStack scratch_;
  std::vector<float> output_;
  const VisemeTrack* speechTrack_ = nullptr;
  float speechTime_ = 0;
  std::array<uint32_t, kSpeechChannelCount> speechCursors_{};
};

}  // namespace facial
