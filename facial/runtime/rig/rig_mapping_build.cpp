// buildRigMapping(): rig map file or scheme detection.
#include <array>
#include <system_error>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/rig/rig_schemes.h"
#include "facial/runtime/rig/rigmap_file.h"

namespace facial {
namespace {

struct SchemeEntry {
  RigScheme scheme;
  SchemeRecognition (*recognise)(std::span<const std::string>);
  void (*map)(RigMappingBuilder&);
  size_t minimumRecognised;  // fewer recognised names than this is a coincidence, not a rig
};

// Detection order: the most specific vocabulary first (CANDIDE names are
// FACS-numbered too; VRM rigs may also carry ARKit custom expressions, which
// are richer than whole emotions; Ready Player Me avatars carry ARKit shapes
// and visemes; VRoid exports carry Fcl_ shapes and sometimes emotion-named
// extras). Visemes last: a face that has nothing else.
constexpr std::array kSchemes = {
    SchemeEntry{RigScheme::Candide3, recogniseCandide3, mapCandide3, 4},
    SchemeEntry{RigScheme::ActionUnits, recogniseActionUnitNames, mapActionUnitNames, 3},
    SchemeEntry{RigScheme::Arkit52, recogniseArkit52, mapArkit52, 10},
    SchemeEntry{RigScheme::VRoid, recogniseVRoid, mapVRoid, 3},
    SchemeEntry{RigScheme::Expressions, recogniseExpressions, mapExpressions, 1},
    SchemeEntry{RigScheme::Visemes, recogniseVisemes, mapVisemes, 3},
};

eng::Result<RigMapping> buildWith(const SchemeEntry& entry, std::span<const std::string> targetNames,
                                  const SchemeRecognition& recognition) {
  RigMappingBuilder builder(entry.scheme, targetNames);
  builder.setDetail(recognition.detail);
  entry.map(builder);
  mapSpeech(builder, entry.scheme);
  return builder.build();
}

}  // namespace

std::filesystem::path rigMapFileFor(const RigMappingOptions& options) {
  if (!options.rigmapFile.empty()) return options.rigmapFile;
  if (options.modelName.empty() || options.rigmapDirectory.empty()) return {};
  // Only the file name part: a model name never walks out of the rig map folder.
  const std::filesystem::path stem = std::filesystem::path(options.modelName).filename();
  const std::filesystem::path rigmap = options.rigmapDirectory / (stem.string() + ".json");
  std::error_code ec;
  return std::filesystem::is_regular_file(rigmap, ec) ? rigmap : std::filesystem::path();
}

eng::Result<RigMapping> buildRigMapping(std::span<const std::string> targetNames, const RigMappingOptions& options) {
  const std::string model = options.modelName.empty() ? std::string("the model") : "'" + options.modelName + "'";
  if (const std::filesystem::path file = rigMapFileFor(options); !file.empty()) {
    auto rigmap = loadRigMapFile(file, targetNames);
    if (!rigmap) return rigmap.error();
    if (rigmap->mapping) return std::move(*rigmap->mapping);
    // A calibration-only file: the detected scheme drives the model.
  }
  std::filesystem::path rigmap;
  if (!options.modelName.empty())
    rigmap = (options.rigmapDirectory.empty() ? std::filesystem::path("data/rigmaps") : options.rigmapDirectory) /
             (std::filesystem::path(options.modelName).filename().string() + ".json");
  for (const SchemeEntry& entry : kSchemes) {
    const SchemeRecognition recognition = entry.recognise(targetNames);
    if (recognition.recognised >= entry.minimumRecognised) return buildWith(entry, targetNames, recognition);
  }
  std::string sample;
  for (size_t i = 0; i < targetNames.size() && i < 4; ++i) sample += (i ? ", " : "") + targetNames[i];
  return eng::makeError(eng::ErrorKind::Unsupported, "rig mapping: no scheme recognises the " + std::to_string(targetNames.size()) +
                        " target names of " + model + (sample.empty() ? "" : " (" + sample + ", ...)") +
                        "; write a rig map " + (rigmap.empty() ? std::string("data/rigmaps/<model>.json") : rigmap.string()));
}

EmotionFeatures emotionFeatures(const RigMapping& rig) {
  EmotionFeatures features;
  for (uint32_t e = 0; e < kEmotionCount; ++e)
    if (Emotion(e) != Emotion::Neutral && !rig.targets(emotionInput(Emotion(e))).empty()) features.emotions = true;
  const std::span<const ActionUnitInfo> channels = actionUnits();
  for (uint32_t c = 0; c < channels.size(); ++c) {
    if (rig.targets(c).empty()) continue;
    const int n = channels[c].facsNumber;
    if (n == 1 || n == 2 || n == 4) features.brows = true;
    if (n == 12 || n == 15) features.lipCorners = true;
  }
  return features;
}

bool showsEmotions(const RigMapping& rig) {
  const EmotionFeatures features = emotionFeatures(rig);
  return features.emotions || (features.brows && features.lipCorners);
}

eng::Result<RigMapping> buildRigMapping(std::span<const std::string> targetNames, RigScheme scheme) {
  for (const SchemeEntry& entry : kSchemes) {
    if (entry.scheme != scheme) continue;
    const SchemeRecognition recognition = entry.recognise(targetNames);
    if (recognition.recognised == 0)
      return eng::makeError(eng::ErrorKind::Unsupported, "rig mapping: the " + std::string(rigSchemeName(scheme)) + " scheme recognises none of the " +
                            std::to_string(targetNames.size()) + " target names");
    return buildWith(entry, targetNames, recognition);
  }
  return eng::makeError(eng::ErrorKind::Unsupported, "rig mapping: " + std::string(rigSchemeName(scheme)) +
                        " is not a built-in scheme (load a rig map file instead)");
}

}  // namespace facial
