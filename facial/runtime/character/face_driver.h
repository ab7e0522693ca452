#pragma once
// One animated face: a graph instance produces channel weights every frame
// and the model's rig turns them into its morph-target weights. The graph may
// speak action units (mapped through a RigMapping) or the model's own target
// names (copied by name). Sized in create(); update() does not allocate.
//
//   auto face = FaceDriver::create(graph, rig, layoutDefaults, /*seed=*/id);
//   face->graph().setTrigger(*graph->findParameter("happy"));
//   face->update(dt);
//   renderer.draw(..., face->targetWeights());
#include <cstdint>
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

  GraphInstance graph_;
  const RigMapping* rig_ = nullptr;           // set when the graph speaks action units
  std::vector<uint32_t> channelToTarget_;     // set when it speaks target names (UINT32_MAX: no such target)
  std::vector<float> targetWeights_;
  std::vector<float> expressionWeights_;
};

}  // namespace facial
