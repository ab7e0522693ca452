#pragma once
// One animated face: a graph instance produces channel weights every frame
// and the model's rig turns them into its morph-target weights. The graph may
// speak action units (mapped through a RigMapping) or the model's own target
// names (copied by name). Sized in create(); update() does not allocate.
//
// Speech (setSpeech): a graph with viseme channels (a speech node) layers it
// itself; for any other action-unit graph the driver samples the track,
// yields the graph's mouth to it (mouth-ownership table,
// speech/viseme_action_units.h) and drives the rig's viseme block.
//
//   auto face = FaceDriver::create(graph, rig, layoutDefaults, /*seed=*/id);
//   face->graph().setTrigger(*graph->findParameter("happy"));
//   face->update(dt);
//   renderer.draw(..., face->targetWeights());
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/graph/graph_instance.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

class FaceDriver {
 public:
  // `rig` maps action units onto the model's flat target list (targetCount ==
  // baseWeights.size()) and must outlive the driver; it may be null when the
  // graph's channels are target names. baseWeights: the model's default
  // weights, kept for targets that nothing drives.
  static eng::Result<FaceDriver> create(SharedGraphDefinition graph, const RigMapping* rig,
                                        std::span<const std::string> targetNames, std::span<const float> baseWeights,
                                        uint64_t seed = 0);

  // Advances the graph by dt seconds and refreshes targetWeights(). False
  // (nothing changes) for a negative or non-finite dt.
  bool update(float dt);

  // The speech played from the next update() on: a track (not owned, must
  // outlive its use; null: none) at the host's audio-clock time. False (no
  // change) for a non-finite time. The caller checks that the rig speaks.
  bool setSpeech(const VisemeTrack* track, float audioTime);

  std::span<const float> targetWeights() const { return targetWeights_; }
  // The rig's expression weights this frame (RigMapping::controlNames()
  // order) when it has an expression stage (VRM), for the expressions'
  // material binds; empty otherwise.
  std::span<const float> expressionWeights() const { return expressionWeights_; }
  std::span<const float> channelWeights() const { return graph_.weights(); }
  GraphInstance& graph() { return graph_; }
  const GraphInstance& graph() const { return graph_; }

 private:
  FaceDriver(GraphInstance graph) : graph_(std::move(graph)) {}
  bool layerSpeech(std::span<const float> graphActionUnits);

  GraphInstance graph_;
  const RigMapping* rig_ = nullptr;           // set when the graph speaks action units
  std::vector<uint32_t> channelToTarget_;     // set when it speaks target names (UINT32_MAX: no such target)
  std::vector<float> targetWeights_;
  std::vector<float> expressionWeights_;
  std::optional<uint32_t> graphVisemes_;   // the graph's first viseme channel (a graph that speaks)
  const VisemeTrack* speech_ = nullptr;
  float speechTime_ = 0;
  std::array<uint32_t, kSpeechChannelCount> speechCursors_{};
  std::array<float, kVisemeCount> visemes_{};
  std::array<float, kMouthChannelCount> mouth_{};
  std::vector<float> auScratch_;           // the graph's action units with the mouth yielded to speech
};

}  // namespace facial
