#pragma once
// Graph files (data/graphs/*.json), version 1. Nodes nest as a tree under
// "root"; parameters and timelines are referred to by name:
//
//   {"version": 1,
//    "channels": "actionUnits",                       // or ["eyeBlink_L", "jawOpen", ...]
//    "parameters": [{"name": "happy", "type": "trigger"},
//                   {"name": "x", "type": "float", "default": 0}],
//    "timelines": {"talk": "timelines/talk.json"},   // path in this file's folder, or inline object
//    "root": {"type": "blink", "input": {
//      "type": "stateMachine", "defaultState": "neutral",
//      "states": [
//        {"name": "neutral", "node": {"type": "pose", "preset": "neutral"},
//         "transitions": [{"to": "happy", "duration": 0.8, "curve": "cosine",
//                          "conditions": [{"parameter": "happy"}]}]},
//        {"name": "happy", "node": {"type": "pose", "preset": "happy", "intensity": 0.9}}],
//      "anyState": [{"to": "neutral", "duration": 0.5, "exitTime": 10}]}}}
//
// Node types and their keys: each node type's header says (nodes/<type>_node.h,
// "JSON:"); inputs are nested node objects, "float inputs" take a number or a
// float parameter's name. The types: pose, blend, bilinear, controlMap,
// freeformMap, additive, timeline, stateMachine, blink (NodeData in node.h).
// Every node may carry a "name" (GraphDefinition::findNode). Curves: see curve_json.h.
// Errors read "file: /root/input/states/2/transitions/0/duration: problem".
#include <filesystem>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "facial/runtime/graph/graph_definition.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/json/json_document.h"

namespace facial {

inline constexpr int kGraphFileVersion = 1;
// Nodes inside nodes (blend in blend in ...); hand-written graphs use a handful.
inline constexpr size_t kMaxGraphNodeDepth = 64;

struct GraphLoadOptions {
  PresetLookup presets;  // empty: a graph that names a preset fails to load, saying so
  // Timeline files a graph names resolve inside the graph's folder (no absolute
  // paths, no `..` out of it, no links out of it), as glTF URIs do; true lifts that
  // for a graph the user trusts (`--allow-outside-paths`).
  bool allowOutsidePaths = false;
  // The load's budget (engine/core/load_budget.h): each node's dense pose and
  // the state it adds to every character are charged as the graph is read.
  size_t maxBytes = eng::kDefaultLoadBudgetBytes;
};

eng::Result<SharedGraphDefinition> loadGraph(const std::filesystem::path& path, const GraphLoadOptions& options = {});
// `source` names the document in messages; timeline paths resolve in its folder. A
// timeline file that fails is named with its error's kind, never its message: that
// would quote the other file's content.
eng::Result<SharedGraphDefinition> parseGraph(const Json& document, const std::filesystem::path& source,
                                              const GraphLoadOptions& options = {});

}  // namespace facial
