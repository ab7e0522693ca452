#pragma once
// Builds a GraphDefinition in C++: declare parameters and timelines, add
// nodes (children first; each add returns the index to wire into parents),
// pick the root, build(). All validation happens in build(), which names the
// node (its origin: a JSON pointer when the graph came from a file, else
// "node 3 (blend)"), the field and the problem.
//
//   GraphBuilder b(ChannelSet::actionUnits());
//   ParameterIndex t = b.addFloat("mix", 0.0f);
//   NodeIndex calm = b.add(PoseNode{.weights = calmWeights});
//   NodeIndex glad = b.add(PoseNode{.weights = gladWeights});
//   b.setRoot(b.add(BlendNode{.a = calm, .b = glad, .factor = FloatInput::bound(t), .curve = EasingCurve::cosine()}));
//   eng::Result<SharedGraphDefinition> graph = b.build();
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "facial/runtime/graph/graph_definition.h"

namespace facial {

class GraphBuilder {
 public:
  // Every node is charged as it is added to a budget of `maxBytes`: what the
  // definition holds for it (its dense pose or mask, a float per channel) and
  // the state it adds to every GraphInstance. Past the budget add() keeps
  // nothing more, budgetError() says which node crossed it, and build() fails
  // with it: a few bytes of JSON per node times thousands of channels never
  // add up to gigabytes.
  explicit GraphBuilder(ChannelSet channels, size_t maxBytes = eng::kDefaultLoadBudgetBytes);

  const ChannelSet& channels() const { return definition_.channels_; }

  ParameterIndex addParameter(std::string name, ParameterType type, float defaultValue = 0.0f);
  ParameterIndex addFloat(std::string name, float defaultValue = 0.0f);
  ParameterIndex addBool(std::string name, bool defaultValue = false);
  ParameterIndex addTrigger(std::string name);
  std::optional<ParameterIndex> findParameter(std::string_view name) const;
  const ParameterDecl& parameter(ParameterIndex p) const { return definition_.parameters_[p]; }

  uint32_t addTimeline(Timeline timeline);
  std::optional<uint32_t> findTimeline(std::string_view name) const;

  NodeIndex add(NodeData node, std::string name = {}, std::string origin = {});  // kNoNode once over the budget
  const std::optional<eng::Error>& budgetError() const { return overBudget_; }
  // A node added earlier, to finish wiring it (e.g. states added after their machine).
  NodeData& node(NodeIndex node) { return definition_.nodes_[node].data; }
  uint32_t nodeCount() const { return static_cast<uint32_t>(definition_.nodes_.size()); }

  void setRoot(NodeIndex root) { definition_.root_ = root; }

  // Validates everything and returns the shareable definition. The builder
  // is left as it was (build again after changes).
  eng::Result<SharedGraphDefinition> build() const;

 private:
  GraphDefinition definition_;
  eng::LoadBudget budget_;
  std::optional<eng::Error> overBudget_;
};

}  // namespace facial
