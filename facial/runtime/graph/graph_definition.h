#pragma once
// The immutable part of an animation graph: channels, parameters, timelines
// and the node tree. Built once (GraphBuilder or loadGraph) and shared by
// every character that runs it; per-character state lives in GraphInstance.
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/name_index.h"
#include "facial/runtime/graph/channel_set.h"
#include "facial/runtime/graph/node.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/graph/timeline.h"

namespace facial {

class GraphDefinition {
 public:
  const ChannelSet& channels() const { return channels_; }
  uint32_t channelCount() const { return channels_.size(); }
  // Floats per pose buffer: the channels, then kPoseLaneCount lanes.
  uint32_t poseStride() const { return channels_.size() + kPoseLaneCount; }

  std::span<const ParameterDecl> parameters() const { return parameters_; }
  std::optional<ParameterIndex> findParameter(std::string_view name) const;

  std::span<const NodeDef> nodes() const { return nodes_; }
  NodeIndex root() const { return root_; }
  std::optional<NodeIndex> findNode(std::string_view name) const;
  template <class T>
  const T* nodeAs(NodeIndex node) const {
    return node < nodes_.size() ? std::get_if<T>(&nodes_[node].data) : nullptr;
  }

  // A node's inputs in evaluation order (flat, precomputed so the per-frame
  // path can walk the tree without building lists).
  std::span<const NodeIndex> inputs(NodeIndex node) const {
    return std::span<const NodeIndex>(inputs_).subspan(inputOffsets_[node], inputOffsets_[node + 1] - inputOffsets_[node]);
  }

  std::span<const Timeline> timelines() const { return timelines_; }

  // Scratch poses one evaluation needs at most (computed from the tree at build).
  uint32_t scratchPoseCount() const { return scratchPoseCount_; }

 private:
  friend class GraphBuilder;
  ChannelSet channels_;
  std::vector<ParameterDecl> parameters_;
  std::vector<Timeline> timelines_;
  std::vector<NodeDef> nodes_;
  // Names in one look-up each (the builder adds to them as it adds the
  // items): a graph file of n names then parses in O(n), not O(n^2).
  eng::NameIndex parameterIndex_, timelineIndex_, nodeIndex_;
  std::vector<NodeIndex> inputs_;
  std::vector<uint32_t> inputOffsets_;  // nodes_.size() + 1 entries
  NodeIndex root_ = kNoNode;
  uint32_t scratchPoseCount_ = 0;
};

using SharedGraphDefinition = std::shared_ptr<const GraphDefinition>;

}  // namespace facial
