#pragma once
// Speech over an expression: the input pose (an emotion, a state machine)
// with its mouth yielding to the host's speech (GraphInstance::setSpeech) by
// the mouth-ownership table (speech/viseme_action_units.h), plus the viseme
// channels sampled from the track at the audio-clock time. The brows, eyes,
// cheeks and head stay the input's, so the state machine can change emotion
// in the middle of a sentence.
//
//   activity = amount * (1 - sil)                 how much speech holds the mouth
//   AU channels: yieldMouthToSpeech(activity, lipClosure)
//   viseme channels: amount * the track's visemes (0 with no track)
//
// The graph's channels must be "actionUnitsAndVisemes" (ChannelSet).
// JSON (graph_json.h): "speech": input, amount (number or parameter, default 1)
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

struct SpeechNode {
  static constexpr std::string_view kType = "speech";  // JSON "type"
  static eng::Result<SpeechNode> read(const JsonNode& j, detail::NodeReader& r);

  NodeIndex input = kNoNode;
  FloatInput amount = FloatInput::fixed(1.0f);  // 0: the input alone, 1: speech owns the mouth while it speaks

  // Derived at build: where the viseme channels start (after the action units).
  uint32_t firstVisemeChannel = 0;

  static constexpr uint32_t kScratchPoses = 0;
  void inputs(std::vector<NodeIndex>& out) const { out.push_back(input); }
  eng::Result<void> prepare(const BuildContext& ctx);
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;
};

}  // namespace facial
