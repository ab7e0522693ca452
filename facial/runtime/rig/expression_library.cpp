#include "facial/runtime/rig/expression_library.h"

#include <algorithm>
#include <cmath>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"

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

// A weight in [0,1]; JSON has no NaN literal, but 1e999 parses to infinity.
eng::Result<float> readWeight(const Json& value, std::string_view source, const std::string& path) {
  if (!value.is_number())
    return jsonError(source, path, "weight must be a number, got " + std::string(jsonTypeName(value)));
  const double w = value.get<double>();
  if (!std::isfinite(w)) return jsonError(source, path, "weight is not a finite number");
  if (w < 0.0 || w > 1.0) return jsonError(source, path, "weight " + formatNumber(w) + " is outside [0, 1]");
  return static_cast<float>(w);
}

eng::Result<std::string> readText(const Json& value, std::string_view source, const std::string& path) {
  if (!value.is_string()) return jsonError(source, path, "must be a string, got " + std::string(jsonTypeName(value)));
  return value.get<std::string>();
}

eng::Result<ExpressionPreset> readPreset(const std::string& name, const Json& body, std::string_view source,
                                         const std::string& path) {
  if (!body.is_object())
    return jsonError(source, path, "an expression must be an object, got " + std::string(jsonTypeName(body)));
  ExpressionPreset preset;
  preset.name = name;
  bool hasEmotions = false;
  for (const auto& [key, value] : body.items()) {
    const std::string keyPath = childPath(path, key);
    if (key == "facs" || key == "description") {
      auto text = readText(value, source, keyPath);
      if (!text) return text.error();
      (key == "facs" ? preset.facs : preset.description) = std::move(*text);
    } else if (key == "actionUnits") {
      if (!value.is_object())
        return jsonError(source, keyPath, "must be an object of channel: weight, got " + std::string(jsonTypeName(value)));
      for (const auto& [channelName, weightValue] : value.items()) {
        const std::string auPath = childPath(keyPath, channelName);
        const std::optional<uint32_t> channel = actionUnitIndex(channelName);
        if (!channel) return jsonError(source, auPath, "unknown action unit (known: " + knownActionUnitNames() + ")");
        auto weight = readWeight(weightValue, source, auPath);
        if (!weight) return weight.error();
        preset.actionUnits.push_back({*channel, *weight});
      }
    } else if (key == "emotions") {
      if (!value.is_object())
        return jsonError(source, keyPath, "must be an object of emotion: weight, got " + std::string(jsonTypeName(value)));
      hasEmotions = true;
      for (const auto& [emotion, weightValue] : value.items()) {
        const std::string emotionPath = childPath(keyPath, emotion);
        const std::optional<uint32_t> index = emotionIndex(emotion);
        if (!index) return jsonError(source, emotionPath, "unknown emotion (known: " + knownEmotionNames(true) + ")");
        auto weight = readWeight(weightValue, source, emotionPath);
        if (!weight) return weight.error();
        preset.emotions[*index] = *weight;
      }
    } else if (key == "components") {
      if (!value.is_array())
        return jsonError(source, keyPath, "must be an array of basic emotions, got " + std::string(jsonTypeName(value)));
      for (size_t i = 0; i < value.size(); ++i) {
        const std::string componentPath = childPath(keyPath, i);
        auto component = readText(value[i], source, componentPath);
        if (!component) return component.error();
        const std::optional<uint32_t> index = emotionIndex(*component);
        if (!index || *index == static_cast<uint32_t>(Emotion::Neutral))
          return jsonError(source, componentPath,
                           "'" + *component + "' is not a basic emotion (known: " + knownEmotionNames(false) + ")");
        const Emotion emotion = static_cast<Emotion>(*index);
        if (std::find(preset.components.begin(), preset.components.end(), emotion) != preset.components.end())
          return jsonError(source, componentPath, "component '" + *component + "' is listed twice");
        preset.components.push_back(emotion);
      }
      if (preset.components.size() < 2)
        return jsonError(source, keyPath,
                         "a compound needs at least 2 components, got " + std::to_string(preset.components.size()));
    } else {
      return jsonError(source, keyPath,
                       "unknown key (expected actionUnits, emotions, components, facs, description)");
    }
  }
  std::sort(preset.actionUnits.begin(), preset.actionUnits.end(),
            [](const ActionUnitWeight& a, const ActionUnitWeight& b) { return a.channel < b.channel; });
  if (!hasEmotions) {
    if (const std::optional<uint32_t> own = emotionIndex(name)) {
      preset.emotions[*own] = 1.0f;
    } else {
      for (Emotion e : preset.components)
        preset.emotions[static_cast<size_t>(e)] = 1.0f / static_cast<float>(preset.components.size());
    }
  }
  return preset;
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
  if (!root.is_object()) return jsonError(source, "", "the document must be an object, got " + std::string(jsonTypeName(root)));
  if (!root.contains("version")) return jsonError(source, "/version", "missing (this build reads version 1)");
  const Json& version = root["version"];
  if (auto supported = checkFormatVersion(version, kFormatVersion); !supported)
    return supported.error().prefixed(std::string(source) + ": /version: ");
  for (const auto& [key, value] : root.items())
    if (key != "version" && key != "expressions")
      return jsonError(source, childPath("", key), "unknown key (expected version, expressions)");
  if (!root.contains("expressions")) return jsonError(source, "/expressions", "missing");
  const Json& expressions = root["expressions"];
  if (!expressions.is_object())
    return jsonError(source, "/expressions", "must be an object of name: expression, got " +
                                                 std::string(jsonTypeName(expressions)));
  ExpressionLibrary library;
  for (const auto& [name, body] : expressions.items()) {
    const std::string path = childPath("/expressions", name);
    if (name.empty()) return jsonError(source, path, "an expression name must not be empty");
    auto preset = readPreset(name, body, source, path);
    if (!preset) return preset.error();
    library.presets_.push_back(std::move(*preset));
  }
  return library;
}

const ExpressionPreset* ExpressionLibrary::find(std::string_view name) const {
  for (const ExpressionPreset& p : presets_)
    if (p.name == name) return &p;
  return nullptr;
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
