#include "facial/runtime/rig/expression_library.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/json/json_node.h"
#include "facial/runtime/rig/action_units.h"

namespace facial {
namespace {

constexpr int kFormatVersion = 1;

std::string knownActionUnitNames() {
  std::string names;
  for (const ActionUnitInfo& au : actionUnits()) names += (names.empty() ? "" : ", ") + std::string(au.name);
  return names;
}

std::string knownEmotionNames(bool withNeutral) {
  std::string names;
  for (std::string_view e : emotionNames())
    if (withNeutral || e != emotionName(Emotion::Neutral)) names += (names.empty() ? "" : ", ") + std::string(e);
  return names;
}

// A weight in [0, 1].
eng::Result<float> readWeight(const JsonNode& value) {
  const float w = ENG_TRY_VALUE(value.number());
  if (w < 0.0f || w > 1.0f) return value.error("weight " + formatNumber(w) + " is outside [0, 1]");
  return w;
}

// {"AU12_LipCornerPuller_L": 1.0, ...}, in ascending channel order.
eng::Result<std::vector<ActionUnitWeight>> readActionUnits(const JsonNode& units) {
  std::vector<ActionUnitWeight> weights;
  for (const auto& [name, weight] : ENG_TRY_VALUE(units.members())) {
    const std::optional<uint32_t> channel = actionUnitIndex(name);
    if (!channel) return weight.error("unknown action unit (known: " + knownActionUnitNames() + ")");
    weights.push_back({*channel, ENG_TRY_VALUE(readWeight(weight))});
  }
  std::sort(weights.begin(), weights.end(),
            [](const ActionUnitWeight& a, const ActionUnitWeight& b) { return a.channel < b.channel; });
  return weights;
}

// {"happy": 0.65, ...}; emotions not named stay 0.
eng::Result<std::array<float, kEmotionCount>> readEmotions(const JsonNode& emotions) {
  std::array<float, kEmotionCount> weights{};
  for (const auto& [name, weight] : ENG_TRY_VALUE(emotions.members())) {
    const std::optional<uint32_t> index = emotionIndex(name);
    if (!index) return weight.error("unknown emotion (known: " + knownEmotionNames(true) + ")");
    weights[*index] = ENG_TRY_VALUE(readWeight(weight));
  }
  return weights;
}

// ["happy", "surprise"]: two or more distinct basic emotions.
eng::Result<std::vector<Emotion>> readComponents(const JsonNode& list) {
  const size_t count = ENG_TRY_VALUE(list.size());
  std::vector<Emotion> components;
  for (size_t i = 0; i < count; ++i) {
    const JsonNode item = list.element(i);
    const std::string name = ENG_TRY_VALUE(item.string());
    const std::optional<uint32_t> index = emotionIndex(name);
    if (!index || *index == static_cast<uint32_t>(Emotion::Neutral))
      return item.error("'" + name + "' is not a basic emotion (known: " + knownEmotionNames(false) + ")");
    const Emotion emotion = static_cast<Emotion>(*index);
    if (std::find(components.begin(), components.end(), emotion) != components.end())
      return item.error("component '" + name + "' is listed twice");
    components.push_back(emotion);
  }
  if (components.size() < 2)
    return list.error("a compound needs at least 2 components, got " + std::to_string(components.size()));
  return components;
}

// Without "emotions": 1 on the preset's own name when it is an emotion, else
// an equal share over the components.
std::array<float, kEmotionCount> defaultEmotions(std::string_view name, const std::vector<Emotion>& components) {
  std::array<float, kEmotionCount> weights{};
  if (const std::optional<uint32_t> own = emotionIndex(name)) {
    weights[*own] = 1.0f;
  } else {
    for (Emotion e : components) weights[static_cast<size_t>(e)] = 1.0f / static_cast<float>(components.size());
  }
  return weights;
}

eng::Result<ExpressionPreset> readPreset(std::string_view name, const JsonNode& body) {
  ENG_TRY(body.allowOnly({"actionUnits", "emotions", "components", "facs", "description"}));
  ExpressionPreset preset;
  preset.name = name;
  preset.facs = ENG_TRY_VALUE(body.stringOr("facs", ""));
  preset.description = ENG_TRY_VALUE(body.stringOr("description", ""));
  if (auto units = body.find("actionUnits")) preset.actionUnits = ENG_TRY_VALUE(readActionUnits(*units));
  if (auto components = body.find("components")) preset.components = ENG_TRY_VALUE(readComponents(*components));
  if (auto emotions = body.find("emotions")) preset.emotions = ENG_TRY_VALUE(readEmotions(*emotions));
  else preset.emotions = defaultEmotions(name, preset.components);
  return preset;
}

eng::Result<std::vector<ExpressionPreset>> readPresets(const JsonNode& root) {
  ENG_TRY(requireVersion(root, kFormatVersion));
  ENG_TRY(root.allowOnly({"version", "expressions"}));
  const JsonNode expressions = ENG_TRY_VALUE(root.at("expressions"));
  std::vector<ExpressionPreset> presets;
  for (const auto& [name, body] : ENG_TRY_VALUE(expressions.members())) {
    if (name.empty()) return body.error("an expression name must not be empty");
    presets.push_back(ENG_TRY_VALUE(readPreset(name, body)));
  }
  return presets;
}

float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }

}  // namespace

float ExpressionPreset::actionUnitWeight(uint32_t channel) const {
  for (const ActionUnitWeight& au : actionUnits)
    if (au.channel == channel) return au.weight;
  return 0.0f;
}

eng::Result<ExpressionLibrary> ExpressionLibrary::load(const std::filesystem::path& path) {
  eng::Result<Json> json = readJsonFile(path);
  if (!json) return json.error();
  return fromJson(*json, path.string());
}

eng::Result<ExpressionLibrary> ExpressionLibrary::parse(std::string_view text, std::string_view source) {
  eng::Result<Json> json = parseJsonText(text, source);
  if (!json) return json.error();
  return fromJson(*json, source);
}

eng::Result<ExpressionLibrary> ExpressionLibrary::fromJson(const Json& root, std::string_view source) {
  auto presets = readPresets(JsonNode(root, ""));
  if (!presets) return presets.error().prefixed(std::string(source) + ": ");
  ExpressionLibrary library;
  library.presets_ = std::move(*presets);
  library.index_.reserve(library.presets_.size());
  for (size_t i = 0; i < library.presets_.size(); ++i) library.index_.add(library.presets_[i].name, static_cast<uint32_t>(i));
  return library;
}

const ExpressionPreset* ExpressionLibrary::find(std::string_view name) const {
  const std::optional<uint32_t> i = index_.find(name);
  return i ? &presets_[*i] : nullptr;
}

std::vector<std::string_view> ExpressionLibrary::names() const {
  std::vector<std::string_view> names;
  names.reserve(presets_.size());
  for (const ExpressionPreset& p : presets_) names.push_back(p.name);
  return names;
}

bool ExpressionLibrary::isCompound(std::string_view name) const {
  const ExpressionPreset* p = find(name);
  return p != nullptr && p->isCompound();
}

eng::Result<void> ExpressionLibrary::evaluate(const ExpressionPreset& preset, float intensity,
                                              std::span<float> auWeights) {
  const size_t channels = actionUnits().size();
  if (auWeights.size() != channels)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': auWeights has " + std::to_string(auWeights.size()) +
                          " entries, expected " + std::to_string(channels) + " (one per action unit channel)");
  if (!std::isfinite(intensity))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': intensity is not finite");
  std::fill(auWeights.begin(), auWeights.end(), 0.0f);
  for (const ActionUnitWeight& au : preset.actionUnits) auWeights[au.channel] = clamp01(au.weight * intensity);
  return {};
}

eng::Result<void> ExpressionLibrary::evaluateEmotions(const ExpressionPreset& preset, float intensity,
                                                      std::span<float> emotionWeights) {
  if (emotionWeights.size() != kEmotionCount)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': emotionWeights has " +
                          std::to_string(emotionWeights.size()) + " entries, expected " +
                          std::to_string(kEmotionCount) + " (one per emotion channel)");
  if (!std::isfinite(intensity))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "expression '" + preset.name + "': intensity is not finite");
  for (size_t i = 0; i < kEmotionCount; ++i) emotionWeights[i] = clamp01(preset.emotions[i] * intensity);
  return {};
}

}  // namespace facial
