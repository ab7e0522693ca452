#pragma once
// What a node type's JSON reader gets from the graph file's parser. Each node
// type reads its own object in its own file:
//
//   struct BlendNode {
//     static constexpr std::string_view kType = "blend";   // the JSON "type"
//     static BlendNode read(const detail::JsonNode& j, detail::NodeReader& r);
//     ...
//   };
//
// and is listed once, in NodeData (node.h); the parser dispatches on kType.
// A reader reports problems with JsonNode::fail (at the value's JSON pointer),
// which throws JsonProblem: like the rest of detail/ this is not installed, and
// parseGraph turns the problem into an eng::Error, so no exception leaves the
// library. Semantic checks that need the whole graph stay in the node's prepare().
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
  NodeIndex node(const JsonNode& j);
  // A parameter named by the string j; fails when the graph declares none.
  ParameterIndex parameter(const JsonNode& j) const;
  ParameterType parameterType(ParameterIndex p) const;
  // parent[key]: a number, a float parameter's name, or absent (fallback).
  FloatInput floatInput(const JsonNode& parent, std::string_view key, float fallback) const;
  // parent["curve"] (curve_json.h), linear when absent.
  EasingCurve curve(const JsonNode& parent) const;
  // A timeline named by the string j in the graph's "timelines".
  uint32_t timeline(const JsonNode& j) const;

  const ChannelSet& channels() const;
  const PresetLookup& presets() const { return presets_; }

 private:
  GraphBuilder& builder_;
  const PresetLookup& presets_;
  size_t depth_ = 0;  // node() calls under way
};

}  // namespace detail
}  // namespace facial
