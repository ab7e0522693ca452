#pragma once
// What a node type's JSON reader gets from the graph file's parser. Each node
// type reads its own object in its own file:
//
//   struct BlendNode {
//     static constexpr std::string_view kType = "blend";   // the JSON "type"
//     static eng::Result<BlendNode> read(const JsonNode& j, detail::NodeReader& r);
//     ...
//   };
//
// and is listed once, in NodeData (node.h); the parser dispatches on kType.
// A reader returns its problems as values at the offending value's JSON
// pointer (JsonNode::error, json/json_node.h); parseGraph puts the file in
// front. Like the rest of detail/ this is not installed. Semantic checks that
// need the whole graph stay in the node's prepare().
#include <cstdint>
#include <string_view>

#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/graph/detail/json_reader.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace facial {

class ChannelSet;
class GraphBuilder;

namespace detail {

class NodeReader {
 public:
  NodeReader(GraphBuilder& builder, const PresetLookup& presets) : builder_(builder), presets_(presets) {}

  // A nested node object (any type), added to the graph; returns its index.
  // Bounds the nesting depth before going down (kMaxGraphNodeDepth).
  eng::Result<NodeIndex> node(const JsonNode& j);
  // A parameter named by the string j; fails when the graph declares none.
  eng::Result<ParameterIndex> parameter(const JsonNode& j) const;
  ParameterType parameterType(ParameterIndex p) const;
  // parent[key]: a number, a float parameter's name, or absent (fallback).
  eng::Result<FloatInput> floatInput(const JsonNode& parent, std::string_view key, float fallback) const;
  // parent["curve"] (curve_json.h), linear when absent.
  eng::Result<EasingCurve> curve(const JsonNode& parent) const;
  // A timeline named by the string j in the graph's "timelines".
  eng::Result<uint32_t> timeline(const JsonNode& j) const;
  // parent[key]: the node object there (required).
  eng::Result<NodeIndex> nodeAt(const JsonNode& parent, std::string_view key) { return node(ENG_TRY_VALUE(parent.at(key))); }

  const ChannelSet& channels() const;
  const PresetLookup& presets() const { return presets_; }

 private:
  GraphBuilder& builder_;
  const PresetLookup& presets_;
  size_t depth_ = 0;  // node() calls under way
};

}  // namespace detail
}  // namespace facial
