#include "editor/timeline_pose.h"

#include <algorithm>

#include "facial/runtime/rig/emotions.h"

namespace editor {

namespace {
uint32_t actionUnitInputs() { return facial::rigInputCount() - uint32_t(facial::kEmotionCount); }
}  // namespace

TimelinePose::TimelinePose(const facial::RigMapping& rig, std::span<const float> baseWeights,
                           const facial::ExpressionLibrary* expressions)
    : rig_(&rig), base_(baseWeights.begin(), baseWeights.end()) {
  for (uint32_t i = 0; i < facial::rigInputCount(); ++i) channelNames_.emplace_back(facial::rigInputName(i));
  for (const std::string& name : rig.targetNames())
    if (std::find(channelNames_.begin(), channelNames_.end(), name) == channelNames_.end()) channelNames_.push_back(name);
  actionUnits_.assign(actionUnitInputs(), 0.0f);
  emotions_.assign(facial::kEmotionCount, 0.0f);
  emotionUnits_.resize(facial::kEmotionCount);
  for (size_t e = 0; e < facial::kEmotionCount && expressions; ++e) {
    const uint32_t input = actionUnitInputs() + uint32_t(e);
    const facial::ExpressionPreset* preset = expressions->find(facial::rigInputName(input));
    if (preset && rig.targets(input).empty()) emotionUnits_[e] = preset->actionUnits;
  }
  if (rig.expressionStage()) expressionWeights_.assign(rig.controlNames().size(), 0.0f);
}

bool TimelinePose::knowsChannel(std::string_view channel) const {
  return std::find(channelNames_.begin(), channelNames_.end(), channel) != channelNames_.end();
}

eng::Result<void> TimelinePose::pose(const TimelineDocument& document, float time, std::span<float> targets) {
  if (targets.size() != base_.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "timeline pose: room for " + std::to_string(targets.size()) + " weights, the model has " +
                          std::to_string(base_.size()));
  std::copy(base_.begin(), base_.end(), targets.begin());
  std::fill(actionUnits_.begin(), actionUnits_.end(), 0.0f);
  std::fill(emotions_.begin(), emotions_.end(), 0.0f);
  unknownTracks_ = 0;
  const auto tracks = document.tracks();
  const auto names = rig_->targetNames();
  for (size_t t = 0; t < tracks.size(); ++t) {
    if (!document.audible(t)) continue;  // muted, or another track is soloed
    if (const auto input = facial::rigInputIndex(tracks[t].channel)) {
      const float value = document.sample(t, time);
      if (*input < actionUnits_.size())
        actionUnits_[*input] = value;
      else
        emotions_[*input - actionUnits_.size()] = value;
    }
  }
  for (size_t e = 0; e < emotions_.size(); ++e)
    for (const facial::ActionUnitWeight& unit : emotionUnits_[e]) actionUnits_[unit.channel] += emotions_[e] * unit.weight;
  if (auto applied = rig_->apply(actionUnits_, emotions_, targets, expressionWeights_); !applied) return applied;
  for (size_t t = 0; t < tracks.size(); ++t) {
    if (!document.audible(t) || facial::rigInputIndex(tracks[t].channel)) continue;
    const auto it = std::find(names.begin(), names.end(), tracks[t].channel);
    if (it == names.end()) {
      ++unknownTracks_;
      continue;
    }
    targets[size_t(it - names.begin())] = document.sample(t, time);
  }
  return {};
}

}  // namespace editor
