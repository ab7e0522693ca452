#include "facial/runtime/graph/preset_lookup.h"

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/expression_library.h"

namespace facial {

PresetLookup presetLookup(const ExpressionLibrary& library) {
  return [&library](std::string_view name, float intensity, std::span<float> auWeights) -> eng::Result<void> {
    const ExpressionPreset* preset = library.find(name);
    if (!preset) {
      std::string known;
      for (std::string_view n : library.names()) known += (known.empty() ? "" : ", ") + std::string(n);
      return eng::makeError(eng::ErrorKind::NotFound, "unknown expression preset '" + std::string(name) + "' (known: " + known + ")");
    }
    return ExpressionLibrary::evaluate(*preset, intensity, auWeights);
  };
}

eng::Result<std::vector<float>> presetPose(const PresetLookup& lookup, std::string_view name, float intensity,
                                           const ChannelSet& channels) {
  if (!lookup) return eng::makeError(eng::ErrorKind::InvalidArgument, "preset '" + std::string(name) + "' requested but no expression library was given");
  std::vector<float> au(actionUnits().size(), 0.0f);
  if (auto r = lookup(name, intensity, au); !r) return r.error();
  std::vector<float> pose(channels.size(), 0.0f);
  for (uint32_t c = 0; c < channels.size(); ++c)
    if (auto index = actionUnitIndex(channels[c].name)) pose[c] = au[*index];
  return pose;
}

}  // namespace facial
