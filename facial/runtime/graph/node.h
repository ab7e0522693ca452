#pragma once
// The closed set of node types and what the graph stores per node: its
// immutable definition (NodeDef) and, per character, its state (NodeState).
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
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/nodes/timeline_node.h"

namespace facial {

using NodeData = std::variant<PoseNode, BlendNode, BilinearNode, ControlMapNode, FreeformMapNode, AdditiveNode,
                              TimelineNode, StateMachineNode, BlinkNode>;

// "pose", "blend", "bilinear", "controlMap", "freeformMap", "additive",
// "timeline", "stateMachine", "blink" (the JSON "type" names).
std::string_view nodeTypeName(const NodeData& data);

struct NodeDef {
  std::string name;    // optional, for findNode()
  std::string origin;  // where it was declared, for messages (JSON pointer, or "node 3 (blend)")
  NodeData data;
};

// Node types that keep per-character state.
template <class T>
concept HasNodeState = requires { typename T::State; };

using NodeState = std::variant<std::monostate, BilinearNode::State, TimelineNode::State, StateMachineNode::State,
                               BlinkNode::State>;

}  // namespace facial
