#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

#include "engine/core/name_index.h"
#include "facial/runtime/json/json_node.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/speech/viseme.h"

namespace facial {
namespace {

constexpr int kFormatVersion = 1;

// A finite number in [lo, hi] (weights, calibration factors).
eng::Result<float> numberIn(const JsonNode& value, float lo, float hi) {
  const float x = ENG_TRY_VALUE(value.number());
  if (x < lo || x > hi)
    return value.error("value " + formatNumber(x) + " is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "]");
  return x;
}

// "weightRange": [min, max], both in [-1, 1].
eng::Result<void> readWeightRange(const JsonNode& range, RigMappingBuilder& builder) {
  const size_t count = ENG_TRY_VALUE(range.size());
  if (count != 2) return range.error("expected [min, max], got " + std::to_string(count) + " numbers");
  const float lo = ENG_TRY_VALUE(numberIn(range.element(0), -1.0f, 1.0f));
  const float hi = ENG_TRY_VALUE(numberIn(range.element(1), -1.0f, 1.0f));
  if (!(lo < hi)) return range.error("min must be below max");
  builder.setWeightRange(lo, hi);
  return {};
}

// The model's targets by name, several to a name where the model repeats
// one: each entry of a rig map finds its targets in one look-up, not a scan
// of every target (a map of n entries on a model of n targets was n^2).
class TargetsByName {
 public:
  explicit TargetsByName(std::span<const std::string> names) : next_(names.size(), kNone) {
    std::vector<uint32_t> last(names.size(), kNone);  // per first target of a name: its last one
    for (uint32_t t = 0; t < names.size(); ++t) {
      if (auto first = index_.find(names[t])) {
        next_[last[*first]] = t;
        last[*first] = t;
      } else {
        index_.add(names[t], t);
        last[t] = t;
      }
    }
  }
  // The first target called `name` (kNone: none), then next(t) for the others.
  uint32_t first(std::string_view name) const { return index_.find(name).value_or(kNone); }
  uint32_t next(uint32_t target) const { return next_[target]; }
  static constexpr uint32_t kNone = UINT32_MAX;

 private:
  eng::NameIndex index_;
  std::vector<uint32_t> next_;
};

// One channel's [{target, weight}]: every target of that name is driven.
eng::Result<void> readChannelTargets(const JsonNode& list, std::string_view channel, uint32_t input,
                                     const TargetsByName& targets, size_t targetCount, RigMappingBuilder& builder) {
  const size_t count = ENG_TRY_VALUE(list.size());
  eng::NameIndex seen;
  for (size_t i = 0; i < count; ++i) {
    const JsonNode entry = list.element(i);
    ENG_TRY(entry.allowOnly({"target", "weight"}));
    const JsonNode targetNode = ENG_TRY_VALUE(entry.at("target"));
    const std::string target = ENG_TRY_VALUE(targetNode.string());
    const float weight = ENG_TRY_VALUE(numberIn(ENG_TRY_VALUE(entry.at("weight")), -1.0f, 1.0f));
    if (!seen.add(target, static_cast<uint32_t>(i)))
      return targetNode.error("'" + target + "' is listed twice for " + std::string(channel));
    const uint32_t first = targets.first(target);
    if (first == TargetsByName::kNone)
      return targetNode.error("the model has no target '" + target + "' (" + std::to_string(targetCount) + " targets)");
    for (uint32_t t = first; t != TargetsByName::kNone; t = targets.next(t)) builder.add(input, t, weight);
  }
  return {};
}

// "map": {channel: [{target, weight}]}, channels are action units or emotions.
eng::Result<void> readMap(const JsonNode& map, std::span<const std::string> targetNames, RigMappingBuilder& builder) {
  const TargetsByName targets(targetNames);
  for (const auto& [channel, list] : ENG_TRY_VALUE(map.members())) {
    const std::optional<uint32_t> input = rigInputIndex(channel);
    if (!input)
      return list.error("unknown channel (an action unit such as AU12_LipCornerPuller_L, "
                        "or an emotion: neutral, happy, sad, surprise, fear, anger, disgust)");
    ENG_TRY(readChannelTargets(list, channel, *input, targets, targetNames.size(), builder));
  }
  return {};
}

// Every target named `target` gets (viseme, gain * shape(viseme)) for each
// viseme whose shape is not zero; false when the model has no such target.
bool addVisemeTarget(std::string_view target, float gain, std::span<const std::string> targetNames,
                     std::span<const float> shape, RigMappingBuilder& builder) {
  bool found = false;
  for (uint32_t t = 0; t < targetNames.size(); ++t) {
    if (targetNames[t] != target) continue;
    found = true;
    for (size_t v = 0; v < kVisemeCount; ++v)
      if (gain * shape[v] != 0.0f) builder.addViseme(Viseme(v), t, gain * shape[v]);
  }
  return found;
}

// What one key of "visemes" drives, per viseme: a viseme drives only itself;
// a mouth channel drives every viseme by its mouth shape (mouthShapeOf),
// except sil, the relaxed mouth, which drives nothing.
std::optional<std::array<float, kVisemeCount>> visemeKeyShape(std::string_view key) {
  std::array<float, kVisemeCount> shape{};
  if (const std::optional<Viseme> viseme = rigVisemeIndex(key)) {
    shape[size_t(*viseme)] = 1.0f;
    return shape;
  }
  for (size_t c = 0; c < kMouthChannelCount; ++c) {
    if (key != mouthChannelName(MouthChannel(c))) continue;
    for (size_t v = 1; v < kVisemeCount; ++v) {
      const MouthShape& m = mouthShapeOf(Viseme(v));
      shape[v] = std::array{m.jawOpen, m.lipClosure, m.lipRounding}[c];
    }
    return shape;
  }
  return std::nullopt;
}

// "visemes": {viseme or mouth channel: {target: weight}}; the visemes are
// the Oculus 15 (any spelling rigVisemeIndex reads), the mouth channels
// jawOpen, lipClosure, lipRounding.
eng::Result<void> readVisemes(const JsonNode& visemes, std::span<const std::string> targetNames,
                              RigMappingBuilder& builder) {
  for (const auto& [key, targets] : ENG_TRY_VALUE(visemes.members())) {
    const std::optional<std::array<float, kVisemeCount>> shape = visemeKeyShape(key);
    if (!shape)
      return targets.error("unknown viseme '" + std::string(key) + "' (expected one of " + visemeNameList() +
                           ", or a mouth channel: jawOpen, lipClosure, lipRounding)");
    for (const auto& [target, weight] : ENG_TRY_VALUE(targets.members())) {
      const float gain = ENG_TRY_VALUE(numberIn(weight, -1.0f, 1.0f));
      if (!addVisemeTarget(target, gain, targetNames, *shape, builder))
        return weight.error("the model has no target '" + std::string(target) + "' (" +
                            std::to_string(targetNames.size()) + " targets)");
    }
  }
  if (!builder.speaks()) return visemes.error("no viseme drives a target (every weight is 0 or the block is empty)");
  return {};
}

// "calibration": {action unit: factor in [0, 4]}.
eng::Result<std::vector<std::pair<std::string, float>>> readCalibration(const JsonNode& calibration) {
  std::vector<std::pair<std::string, float>> factors;
  for (const auto& [channel, scale] : ENG_TRY_VALUE(calibration.members())) {
    const std::optional<uint32_t> input = rigInputIndex(channel);
    if (!input || *input >= actionUnits().size())
      return scale.error("unknown action unit channel (such as AU12_LipCornerPuller_L)");
    factors.emplace_back(channel, ENG_TRY_VALUE(numberIn(scale, 0.0f, 4.0f)));
  }
  return factors;
}

eng::Result<RigMapFile> readRigMapFile(const JsonNode& root, std::string_view source,
                                       std::span<const std::string> targetNames) {
  ENG_TRY(requireVersion(root, kFormatVersion));
  ENG_TRY(root.allowOnly({"version", "model", "description", "weightRange", "map", "visemes", "calibration"}));
  ENG_TRY(root.stringOr("model", ""));  // informational: only the type is checked
  ENG_TRY(root.stringOr("description", ""));
  RigMapFile file;
  if (auto calibration = root.find("calibration")) file.calibration = ENG_TRY_VALUE(readCalibration(*calibration));
  const std::optional<JsonNode> map = root.find("map");
  const std::optional<JsonNode> visemes = root.find("visemes");
  if (!map && !visemes) {
    if (file.calibration.empty()) return root.error("missing \"map\" (a file without a map must calibrate)");
    return file;  // calibration only: the detected scheme drives the model
  }
  if (!map && !file.calibration.empty())
    return root.error("\"visemes\" without \"map\" replaces the detected scheme, so there is nothing to calibrate; "
                      "add a \"map\" or drop the \"calibration\"");
  RigMappingBuilder builder(RigScheme::Custom, targetNames);
  builder.setDetail("rig map " + std::string(source));
  if (auto range = root.find("weightRange")) ENG_TRY(readWeightRange(*range, builder));
  if (map) ENG_TRY(readMap(*map, targetNames, builder));
  if (visemes) {
    ENG_TRY(readVisemes(*visemes, targetNames, builder));
    builder.setSpeech("the rig map's \"visemes\" block");
  } else {
    mapSpeech(builder, RigScheme::Custom);  // viseme_* targets, or the lip and jaw units the map binds
  }
  file.mapping = ENG_TRY_VALUE(builder.build());
  return file;
}

eng::Result<RigMapFile> rigMapFileFromJson(const Json& document, std::string_view source,
                                           std::span<const std::string> targetNames) {
  auto file = readRigMapFile(JsonNode(document, ""), source, targetNames);
  if (!file) return file.error().prefixed(std::string(source) + ": ");
  return file;
}

eng::Result<RigMapping> mappingOf(eng::Result<RigMapFile> file, std::string_view source) {
  if (!file) return file.error();
  if (!file->mapping)
    return eng::makeError(eng::ErrorKind::Malformed, std::string(source) + ": /: missing \"map\" (the file only calibrates)");
  return std::move(*file->mapping);
}

}  // namespace

eng::Result<RigMapFile> loadRigMapFile(const std::filesystem::path& file, std::span<const std::string> targetNames) {
  eng::Result<Json> json = readJsonFile(file);
  if (!json) return json.error();
  return rigMapFileFromJson(*json, file.string(), targetNames);
}

eng::Result<RigMapping> loadRigMap(const std::filesystem::path& file, std::span<const std::string> targetNames) {
  return mappingOf(loadRigMapFile(file, targetNames), file.string());
}

eng::Result<RigMapping> parseRigMap(std::string_view text, std::string_view source,
                                    std::span<const std::string> targetNames) {
  eng::Result<Json> json = parseJsonText(text, source);
  if (!json) return json.error();
  return mappingOf(rigMapFileFromJson(*json, source, targetNames), source);
}

}  // namespace facial
