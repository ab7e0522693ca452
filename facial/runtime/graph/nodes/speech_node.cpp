#include "facial/runtime/graph/nodes/speech_node.h"

#include <algorithm>
#include <array>

#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/nodes/build_context.h"
#include "facial/runtime/graph/nodes/eval_context.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/speech/viseme_action_units.h"

namespace facial {

using detail::NodeReader;

eng::Result<void> SpeechNode::prepare(const BuildContext& ctx) {
  const std::optional<uint32_t> first = ctx.channels.firstVisemeChannel();
  if (!first)
    return ctx.problem("", "a speech node needs the graph's channels to be \"actionUnitsAndVisemes\" (the action "
                           "units, then viseme_sil .. viseme_U)");
  firstVisemeChannel = *first;
  return ctx.checkInput(amount, "amount");
}

void SpeechNode::evaluate(EvalContext& ctx, NodeIndex, std::span<float> out) const {
  ctx.evaluate(input, out);
  const std::span<float> visemeChannels = out.subspan(firstVisemeChannel, kVisemeCount);
  const float share = std::clamp(ctx.read(amount), 0.0f, 1.0f);
  std::array<float, kVisemeCount> visemes{};
  std::array<float, kMouthChannelCount> mouth{};
  float ownership = 0.0f;
  const VisemeSampleJob job{.track = ctx.speech.track, .time = ctx.speech.time, .cursors = ctx.speech.cursors,
                            .visemes = visemes, .mouth = mouth, .ownership = &ownership};
  // No track (or none that samples): the input's own mouth, no visemes.
  if (!ctx.speech.track || share <= 0.0f || !job.Run()) {
    for (float& v : visemeChannels) v *= 1.0f - share;
    return;
  }
  yieldMouthToSpeech(out.first(firstVisemeChannel), share * ownership,
                     mouth[static_cast<size_t>(MouthChannel::LipClosure)]);
  for (size_t v = 0; v < kVisemeCount; ++v) visemeChannels[v] += share * (visemes[v] - visemeChannels[v]);
}

eng::Result<SpeechNode> SpeechNode::read(const JsonNode& j, NodeReader& r) {
  ENG_TRY(j.allowOnly({"type", "name", "input", "amount"}));
  SpeechNode s;
  s.input = ENG_TRY_VALUE(r.nodeAt(j, "input"));
  s.amount = ENG_TRY_VALUE(r.floatInput(j, "amount", 1.0f));
  return s;
}

}  // namespace facial
