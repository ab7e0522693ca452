#include "facial/runtime/graph/emotion_states.h"

#include "facial/runtime/rig/emotions.h"

namespace facial {

eng::Result<std::vector<MachineState>> addEmotionStates(GraphBuilder& builder, const PresetLookup& presets,
                                                        float intensity) {
  std::vector<MachineState> states;
  for (std::string_view emotion : emotionNames()) {
    auto weights = presetPose(presets, emotion, intensity, builder.channels());
    if (!weights) return weights.error();
    const NodeIndex pose = builder.add(PoseNode{.weights = std::move(weights).value()}, std::string(emotion));
    states.push_back({std::string(emotion), pose, {}});
  }
  return states;
}

}  // namespace facial
