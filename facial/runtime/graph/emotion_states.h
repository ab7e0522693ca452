#pragma once
// Convenience for emotion state machines: one state per basic emotion of the
// rig layer's vocabulary (emotionNames(): neutral, happy, sad, surprise,
// fear, anger, disgust), each a pose node holding that expression preset.
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace facial {

// Adds the pose nodes to `builder` and returns the states (named like the
// emotions, no transitions yet) to put into a StateMachineNode.
eng::Result<std::vector<MachineState>> addEmotionStates(GraphBuilder& builder, const PresetLookup& presets,
                                                        float intensity = 1.0f);

}  // namespace facial
