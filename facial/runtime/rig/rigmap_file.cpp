#include "facial/runtime/rig/rigmap_file.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"

namespace facial {
namespace {

eng::Result<float> readNumber(const Json& value, std::string_view source, const std::string& path, double lo,
                              double hi) {
  if (!value.is_number())
    return jsonError(source, path, "must be a number, got " + std::string(jsonTypeName(value)));
  const double x = value.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    return jsonError(source, path,
                     "value " + formatNumber(x) + " is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "]");
  return static_cast<float>(x);
}

eng::Result<RigMapFile> fromJson(const Json& root, std::string_view source, std::span<const std::string> targetNames) {
  RigMapFile file;
  if (!root.is_object()) return jsonError(source, "", "the document must be an object, got " + std::string(jsonTypeName(root)));
  if (!root.contains("version")) return jsonError(source, "/version", "missing (this build reads version 1)");
  if (auto supported = checkFormatVersion(root["version"], 1); !supported)
    return supported.error().prefixed(std::string(source) + ": /version: ");

  RigMappingBuilder builder(RigScheme::Custom, targetNames);
  builder.setDetail("rig map " + std::string(source));
  bool hasMap = false;
  for (const auto& [key, value] : root.items()) {
    const std::string path = childPath("", key);
    if (key == "version") continue;
    if (key == "model" || key == "description") {
      if (!value.is_string()) return jsonError(source, path, "must be a string, got " + std::string(jsonTypeName(value)));
    } else if (key == "weightRange") {
      if (!value.is_array() || value.size() != 2)
        return jsonError(source, path, "must be an array [min, max]");
      auto lo = readNumber(value[0], source, childPath(path, size_t{0}), -1.0, 1.0);
      if (!lo) return lo.error();
      auto hi = readNumber(value[1], source, childPath(path, size_t{1}), -1.0, 1.0);
      if (!hi) return hi.error();
      if (!(*lo < *hi)) return jsonError(source, path, "min must be below max");
      builder.setWeightRange(*lo, *hi);
    } else if (key == "map") {
      if (!value.is_object())
        return jsonError(source, path, "must be an object of channel: [{target, weight}], got " +
                                           std::string(jsonTypeName(value)));
      hasMap = true;
      for (const auto& [channel, list] : value.items()) {
        const std::string channelPath = childPath(path, channel);
        const std::optional<uint32_t> input = rigInputIndex(channel);
        if (!input)
          return jsonError(source, channelPath, "unknown channel (an action unit such as AU12_LipCornerPuller_L, "
                                                "or an emotion: neutral, happy, sad, surprise, fear, anger, disgust)");
        if (!list.is_array())
          return jsonError(source, channelPath, "must be an array of {target, weight}, got " +
                                                    std::string(jsonTypeName(list)));
        std::vector<std::string> seen;
        for (size_t i = 0; i < list.size(); ++i) {
          const std::string entryPath = childPath(channelPath, i);
          const Json& entry = list[i];
          if (!entry.is_object()) return jsonError(source, entryPath, "must be an object {target, weight}");
          for (const auto& [field, _] : entry.items())
            if (field != "target" && field != "weight")
              return jsonError(source, childPath(entryPath, field), "unknown key (expected target, weight)");
          if (!entry.contains("target") || !entry["target"].is_string())
            return jsonError(source, childPath(entryPath, "target"), "missing or not a string");
          if (!entry.contains("weight")) return jsonError(source, childPath(entryPath, "weight"), "missing");
          const std::string target = entry["target"].get<std::string>();
          auto weight = readNumber(entry["weight"], source, childPath(entryPath, "weight"), -1.0, 1.0);
          if (!weight) return weight.error();
          if (std::find(seen.begin(), seen.end(), target) != seen.end())
            return jsonError(source, childPath(entryPath, "target"), "'" + target + "' is listed twice for " + channel);
          seen.push_back(target);
          bool found = false;
          for (uint32_t t = 0; t < targetNames.size(); ++t) {
            if (targetNames[t] != target) continue;
            builder.add(*input, t, *weight);
            found = true;
          }
          if (!found)
            return jsonError(source, childPath(entryPath, "target"),
                             "the model has no target '" + target + "' (" + std::to_string(targetNames.size()) +
                                 " targets)");
        }
      }
    } else if (key == "calibration") {
      if (!value.is_object())
        return jsonError(source, path, "must be an object of action unit: scale, got " + std::string(jsonTypeName(value)));
      for (const auto& [channel, scale] : value.items()) {
        const std::string channelPath = childPath(path, channel);
        const std::optional<uint32_t> input = rigInputIndex(channel);
        if (!input || *input >= actionUnits().size())
          return jsonError(source, channelPath, "unknown action unit channel (such as AU12_LipCornerPuller_L)");
        auto factor = readNumber(scale, source, channelPath, 0.0, 4.0);
        if (!factor) return factor.error();
        file.calibration.emplace_back(channel, *factor);
      }
    } else {
      return jsonError(source, path, "unknown key (expected version, model, description, weightRange, map, calibration)");
    }
  }
  if (!hasMap) {
    if (file.calibration.empty()) return jsonError(source, "/map", "missing (a file without a map must calibrate)");
    return file;  // calibration only: the detected scheme drives the model
  }
  eng::Result<RigMapping> mapping = builder.build();
  if (!mapping) return mapping.error().prefixed(std::string(source) + ": ");
  file.mapping = std::move(*mapping);
  return file;
}

eng::Result<RigMapping> mappingOf(eng::Result<RigMapFile> file, std::string_view source) {
  if (!file) return file.error();
  if (!file->mapping) return jsonError(source, "/map", "missing");
  return std::move(*file->mapping);
}

}  // namespace

eng::Result<RigMapFile> loadRigMapFile(const std::filesystem::path& file, std::span<const std::string> targetNames) {
  eng::Result<Json> json = readJsonFile(file);
  if (!json) return json.error();
  return fromJson(*json, file.string(), targetNames);
}

eng::Result<RigMapping> loadRigMap(const std::filesystem::path& file, std::span<const std::string> targetNames) {
  return mappingOf(loadRigMapFile(file, targetNames), file.string());
}

eng::Result<RigMapping> parseRigMap(std::string_view text, std::string_view source,
                                    std::span<const std::string> targetNames) {
  eng::Result<Json> json = parseJsonText(text, source);
  if (!json) return json.error();
  return mappingOf(fromJson(*json, source, targetNames), source);
}

}  // namespace facial
