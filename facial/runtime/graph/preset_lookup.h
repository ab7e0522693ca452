#pragma once
// Where pose nodes get expression presets: a lookup from preset name and
// intensity to action-unit weights. The rig layer's ExpressionLibrary is the
// usual source (presetLookup(library)); tests and tools may supply any
// function with the same contract.
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/graph/channel_set.h"

namespace facial {

class ExpressionLibrary;

// Writes preset `name` at `intensity` into auWeights (actionUnits().size()
// floats); fails naming an unknown preset.
using PresetLookup = std::function<eng::Result<void>(std::string_view name, float intensity, std::span<float> auWeights)>;

// Adapter over the rig layer's library. The library must outlive the lookup.
PresetLookup presetLookup(const ExpressionLibrary& library);

// A preset as a pose over `channels`: action-unit weights land on the
// channels of the same name; channels that are no action unit get 0 (a rig
// of raw morph targets needs its rig map applied to the AU pose instead).
eng::Result<std::vector<float>> presetPose(const PresetLookup& lookup, std::string_view name, float intensity,
                                           const ChannelSet& channels);

}  // namespace facial
