#pragma once
// The closed set of node types and what the graph stores per node: its
// immutable definition (NodeDef) and, per character, its state (NodeState).
// A node type is its own file under nodes/ (struct, kType, read(), prepare(),
// evaluate(), optionally State) plus its entry in NodeData below; the JSON
// reader, the type names and NodeState follow from that list.
#include <string>
#include <string_view>
#include <variant>

#include "facial/runtime/graph/nodes/additive_node.h"
#include "facial/runtime/graph/nodes/bilinear_node.h"
#include "facial/runtime/graph/nodes/blend_node.h"
#include "facial/runtime/graph/nodes/blink_node.h"
#include "facial/runtime/graph/nodes/control_map_node.h"
#include "facial/runtime/graph/nodes/freeform_map_node.h"
#include "facial/runtime/graph/nodes/pose_node.h"
#include "facial/runtime/graph/nodes/speech_node.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/nodes/timeline_node.h"

namespace facial {

using NodeData = std::variant<PoseNode, BlendNode, BilinearNode, ControlMapNode, FreeformMapNode, AdditiveNode,
                              TimelineNode, StateMachineNode, BlinkNode, SpeechNode>;

// The node's JSON "type" name (its kType).
std::string_view nodeTypeName(const NodeData& data);

struct NodeDef {
  std::string name;    // optional, for findNode()
  std::string origin;  // where it was declared, for messages (JSON pointer, or "node 3 (blend)")
  NodeData data;
};

// Node types that keep per-character state.
template <class T>
concept HasNodeState = requires { typename T::State; };

namespace detail {
// std::variant<std::monostate, T::State...> over the NodeData alternatives T that have a State.
template <class Variant, class Node, bool = HasNodeState<Node>>
struct WithState {
  using type = Variant;
};
template <class... States, class Node>
struct WithState<std::variant<States...>, Node, true> {
  using type = std::variant<States..., typename Node::State>;
};
template <class Variant, class... Nodes>
struct StatesOf {
  using type = Variant;
};
template <class Variant, class Node, class... Rest>
struct StatesOf<Variant, Node, Rest...> {
  using type = typename StatesOf<typename WithState<Variant, Node>::type, Rest...>::type;
};
template <class>
struct NodeStatesOf;
template <class... Nodes>
struct NodeStatesOf<std::variant<Nodes...>> {
  using type = typename StatesOf<std::variant<std::monostate>, Nodes...>::type;
};
}  // namespace detail

// Per character, per node: the node type's State, or monostate.
using NodeState = typename detail::NodeStatesOf<NodeData>::type;

}  // namespace facial
