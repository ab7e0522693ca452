#include "facial/runtime/character/face_driver.h"

#include <limits>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/speech/viseme_action_units.h"

namespace facial {
namespace {

bool speaksActionUnits(const ChannelSet& channels) {
  const auto aus = actionUnits();
  if (channels.size() != aus.size()) return false;
  for (uint32_t i = 0; i < aus.size(); ++i)
    if (channels.channels()[i].name != aus[i].name) return false;
  return true;
}

}  // namespace

eng::Result<FaceDriver> FaceDriver::create(SharedGraphDefinition graph, const RigMapping* rig,
                                           std::span<const std::string> targetNames,
                                           std::span<const float> baseWeights, uint64_t seed) {
  if (!graph) return eng::makeError(eng::ErrorKind::InvalidArgument, "face driver: no graph");
  if (targetNames.size() != baseWeights.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "face driver: " + std::to_string(targetNames.size()) + " target names but " +
                          std::to_string(baseWeights.size()) + " base weights");
  const ChannelSet& channels = graph->channels();
  auto instance = GraphInstance::create(graph, seed);
  if (!instance) return instance.error();
  FaceDriver driver(std::move(*instance));
  driver.targetWeights_.assign(baseWeights.begin(), baseWeights.end());

  driver.graphVisemes_ = channels.firstVisemeChannel();
  if (speaksActionUnits(channels) || driver.graphVisemes_) {
    if (!rig) return eng::makeError(eng::ErrorKind::Unsupported, "face driver: the graph drives action units but the model has no rig mapping");
    if (rig->targetCount() != baseWeights.size())
      return eng::makeError(eng::ErrorKind::InvalidArgument, "face driver: rig mapping covers " + std::to_string(rig->targetCount()) +
                            " targets, the model has " + std::to_string(baseWeights.size()));
    driver.rig_ = rig;
    driver.auScratch_.assign(actionUnits().size(), 0.0f);
    if (rig->expressionStage()) driver.expressionWeights_.assign(rig->controlNames().size(), 0.0f);
    return driver;
  }
  // Raw target channels: match by name; a channel the model lacks is an error
  // because its animation would silently do nothing.
  driver.channelToTarget_.assign(channels.size(), std::numeric_limits<uint32_t>::max());
  for (uint32_t c = 0; c < channels.size(); ++c) {
    const std::string& name = channels.channels()[c].name;
    for (uint32_t t = 0; t < targetNames.size(); ++t)
      if (targetNames[t] == name) { driver.channelToTarget_[c] = t; break; }
    if (driver.channelToTarget_[c] == std::numeric_limits<uint32_t>::max())
      return eng::makeError(eng::ErrorKind::NotFound, "face driver: graph channel '" + name + "' is no morph target of the model");
  }
  return driver;
}

bool FaceDriver::setSpeech(const VisemeTrack* track, float audioTime) {
  if (!graph_.setSpeech(track, audioTime)) return false;
  speech_ = track;
  speechTime_ = audioTime;
  return true;
}

// The graph's action units with the mouth yielded to the track's visemes
// (into auScratch_ and visemes_); false when there is nothing to say.
bool FaceDriver::layerSpeech(std::span<const float> graphActionUnits) {
  float ownership = 0.0f;
  const VisemeSampleJob job{.track = speech_, .time = speechTime_, .cursors = speechCursors_, .visemes = visemes_,
                            .mouth = mouth_, .ownership = &ownership};
  if (!speech_ || !job.Run()) return false;
  std::copy(graphActionUnits.begin(), graphActionUnits.end(), auScratch_.begin());
  yieldMouthToSpeech(auScratch_, ownership, mouth_[static_cast<size_t>(MouthChannel::LipClosure)]);
  return true;
}

bool FaceDriver::update(float dt) {
  if (!graph_.update(dt)) return false;
  const std::span<const float> weights = graph_.weights();
  if (rig_) {
    // Sizes were checked in create(), so the rig cannot fail here.
    const size_t units = actionUnits().size();
    if (graphVisemes_ && speech_)
      (void)rig_->applyWithVisemes(weights.first(units), {}, weights.subspan(*graphVisemes_, kVisemeCount), targetWeights_,
                                   expressionWeights_);
    else if (!graphVisemes_ && layerSpeech(weights))
      (void)rig_->applyWithVisemes(auScratch_, {}, visemes_, targetWeights_, expressionWeights_);
    else
      (void)rig_->apply(weights.first(units), {}, targetWeights_, expressionWeights_);
  } else {
    for (size_t c = 0; c < channelToTarget_.size(); ++c) targetWeights_[channelToTarget_[c]] = weights[c];
  }
  return true;
}

}  // namespace facial
