#include "dataset/dataset_spec.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "app/view_options.h"
#include "dataset/light_rigs.h"
#include "engine/scene/file_bytes.h"
#include "facial/runtime/json/json_node.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/expression_library.h"

namespace dataset {
namespace {

using facial::Json;
using facial::JsonNode;

eng::Error specError(const DatasetSpec& spec, std::string_view field, const std::string& problem,
                     eng::ErrorKind kind = eng::ErrorKind::InvalidArgument) {
  return eng::makeError(kind, spec.source + ": " + std::string(field) + ": " + problem);
}

eng::Result<Range> readRange(const JsonNode& node) {
  if (node.isNumber()) {
    const float value = ENG_TRY_VALUE(node.number());
    return Range{value, value};
  }
  const size_t size = ENG_TRY_VALUE(node.size());
  if (size != 2) return node.error("a range is [min, max] or one number, got " + std::to_string(size) + " numbers");
  const float min = ENG_TRY_VALUE(node.element(0).number());
  const float max = ENG_TRY_VALUE(node.element(1).number());
  return Range{min, max};
}

eng::Result<std::vector<std::string>> readNames(const JsonNode& node) {
  const size_t size = ENG_TRY_VALUE(node.size());
  std::vector<std::string> names;
  for (size_t i = 0; i < size; ++i) names.push_back(ENG_TRY_VALUE(node.element(i).string()));
  return names;
}

// A whole number in [0, 2^64): JSON numbers past 2^24 do not fit a float.
eng::Result<uint64_t> readWhole(const JsonNode& node) {
  const Json& value = node.raw();
  if (value.is_number_unsigned()) return value.get<uint64_t>();
  if (value.is_number_integer() && value.get<int64_t>() >= 0) return uint64_t(value.get<int64_t>());
  if (value.is_number_float()) return node.error("must be a whole number, got " + facial::formatNumber(value.get<double>()));
  if (value.is_number()) return node.error("must not be negative, got " + std::to_string(value.get<int64_t>()));
  return node.error(std::string("must be a whole number, got ") + std::string(facial::jsonTypeName(value)));
}

eng::Result<AuMix> readAuMix(const JsonNode& node) {
  ENG_TRY(node.allowOnly({"probability", "units", "weight"}));
  AuMix mix;
  mix.probability = ENG_TRY_VALUE(node.numberOr("probability", 0.0f));
  if (auto units = node.find("units")) {
    const Range range = ENG_TRY_VALUE(readRange(*units));
    if (range.min < 0.0f || range.max < 0.0f || range.min != std::floor(range.min) || range.max != std::floor(range.max))
      return units->error("unit counts must be whole numbers");
    mix.minUnits = uint32_t(std::min(range.min, 1e6f));
    mix.maxUnits = uint32_t(std::min(range.max, 1e6f));
  }
  if (auto weight = node.find("weight")) mix.weight = ENG_TRY_VALUE(readRange(*weight));
  return mix;
}

eng::Result<void> readSize(DatasetSpec& spec, const JsonNode& node) {
  const std::string text = ENG_TRY_VALUE(node.string());
  unsigned w = 0, h = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%ux%u%c", &w, &h, &extra) != 2) return node.error("'" + text + "' is not WIDTHxHEIGHT");
  spec.width = w, spec.height = h;
  return {};
}

eng::Result<void> readFields(DatasetSpec& spec, const JsonNode& root) {
  ENG_TRY(root.allowOnly({"format", "version", "about", "count", "seed", "size", "models", "emotions", "intensity",
                          "auMix", "yaw", "pitch", "zoom", "lights", "backgrounds", "quality"}));
  if (root.has("version")) ENG_TRY(facial::requireVersion(root, 1));
  if (auto format = root.find("format"); format && ENG_TRY_VALUE(format->string()) != "facial-dataset-spec")
    return format->error("expected \"facial-dataset-spec\"");
  if (auto n = root.find("count")) spec.count = ENG_TRY_VALUE(readWhole(*n));
  if (auto n = root.find("seed")) spec.seed = ENG_TRY_VALUE(readWhole(*n));
  if (auto n = root.find("size")) ENG_TRY(readSize(spec, *n));
  if (auto n = root.find("models")) spec.models = ENG_TRY_VALUE(readNames(*n));
  if (auto n = root.find("emotions")) spec.emotions = ENG_TRY_VALUE(readNames(*n));
  if (auto n = root.find("intensity")) spec.intensity = ENG_TRY_VALUE(readRange(*n));
  if (auto n = root.find("auMix")) spec.auMix = ENG_TRY_VALUE(readAuMix(*n));
  if (auto n = root.find("yaw")) spec.yaw = ENG_TRY_VALUE(readRange(*n));
  if (auto n = root.find("pitch")) spec.pitch = ENG_TRY_VALUE(readRange(*n));
  if (auto n = root.find("zoom")) spec.zoom = ENG_TRY_VALUE(readRange(*n));
  if (auto n = root.find("lights")) spec.lights = ENG_TRY_VALUE(readNames(*n));
  if (auto n = root.find("backgrounds")) spec.backgrounds = ENG_TRY_VALUE(readNames(*n));
  if (auto n = root.find("quality")) spec.quality = ENG_TRY_VALUE(n->string());
  for (std::string& emotion : spec.emotions) emotion = canonicalEmotionName(emotion);
  return {};
}

eng::Result<void> checkRange(const DatasetSpec& spec, std::string_view field, Range range, float lo, float hi) {
  if (range.min > range.max)
    return specError(spec, field, "min " + facial::formatNumber(range.min) + " is above max " + facial::formatNumber(range.max));
  if (range.min < lo || range.max > hi)
    return specError(spec, field, "[" + facial::formatNumber(range.min) + ", " + facial::formatNumber(range.max) +
                                      "] is outside [" + facial::formatNumber(lo) + ", " + facial::formatNumber(hi) + "]");
  return {};
}

eng::Result<void> checkNumbers(const DatasetSpec& spec) {
  if (spec.count == 0) return specError(spec, "/count", "must be at least 1 (how many images to make)");
  if (spec.count > kMaxItems)
    return specError(spec, "/count", std::to_string(spec.count) + " is over the limit of " + std::to_string(kMaxItems) +
                                         " images per dataset (split it into several)", eng::ErrorKind::TooLarge);
  if (spec.width == 0 || spec.height == 0 || spec.width > kMaxImageSide || spec.height > kMaxImageSide)
    return specError(spec, "/size", std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                        " is outside 1.." + std::to_string(kMaxImageSide) + " pixels a side");
  ENG_TRY(checkRange(spec, "/intensity", spec.intensity, 0.0f, 1.0f));
  ENG_TRY(checkRange(spec, "/yaw", spec.yaw, -90.0f, 90.0f));
  ENG_TRY(checkRange(spec, "/pitch", spec.pitch, -60.0f, 60.0f));
  ENG_TRY(checkRange(spec, "/zoom", spec.zoom, 0.25f, 4.0f));
  ENG_TRY(checkRange(spec, "/auMix/probability", {spec.auMix.probability, spec.auMix.probability}, 0.0f, 1.0f));
  ENG_TRY(checkRange(spec, "/auMix/weight", spec.auMix.weight, 0.0f, 1.0f));
  const float unitCount = float(facial::actionUnits().size());
  ENG_TRY(checkRange(spec, "/auMix/units", {float(spec.auMix.minUnits), float(spec.auMix.maxUnits)}, 0.0f, unitCount));
  return {};
}

eng::Result<void> checkList(const DatasetSpec& spec, std::string_view field, const std::vector<std::string>& list,
                            size_t limit) {
  if (list.empty()) return specError(spec, field, "is empty (name at least one)");
  if (list.size() > limit)
    return specError(spec, field, std::to_string(list.size()) + " entries, over the limit of " + std::to_string(limit),
                     eng::ErrorKind::TooLarge);
  return {};
}

eng::Result<void> checkNames(const DatasetSpec& spec, const std::filesystem::path& expressionsFile) {
  ENG_TRY(checkList(spec, "/models", spec.models, kMaxModels));
  ENG_TRY(checkList(spec, "/emotions", spec.emotions, 1000));
  ENG_TRY(checkList(spec, "/lights", spec.lights, 1000));
  ENG_TRY(checkList(spec, "/backgrounds", spec.backgrounds, 1000));
  for (size_t i = 0; i < spec.models.size(); ++i) {
    const std::filesystem::path file = modelFile(spec, i);
    std::error_code ec;
    if (!file.empty() && !std::filesystem::is_regular_file(file, ec) && !std::filesystem::is_directory(file, ec))
      return specError(spec, "/models/" + std::to_string(i), "no such model file '" + file.string() + "' ('" +
                                                                 kBuiltInModel + "' is the built-in head)", eng::ErrorKind::NotFound);
  }
  auto library = facial::ExpressionLibrary::load(expressionsFile);
  if (!library) return library.error();
  for (size_t i = 0; i < spec.emotions.size(); ++i) {
    if (library->find(spec.emotions[i])) continue;
    std::string known;
    for (std::string_view name : library->names()) known += (known.empty() ? "" : ", ") + std::string(name);
    return specError(spec, "/emotions/" + std::to_string(i), "unknown emotion '" + spec.emotions[i] + "' (known: " + known + ")",
                     eng::ErrorKind::NotFound);
  }
  for (size_t i = 0; i < spec.lights.size(); ++i) {
    if (findLightRig(spec.lights[i])) continue;
    std::string known;
    for (const NamedLightRig& rig : lightRigs()) known += (known.empty() ? "" : ", ") + std::string(rig.name);
    return specError(spec, "/lights/" + std::to_string(i), "unknown light rig '" + spec.lights[i] + "' (known: " + known + ")",
                     eng::ErrorKind::NotFound);
  }
  for (size_t i = 0; i < spec.backgrounds.size(); ++i)
    if (auto backdrop = app::parseBackground(spec.backgrounds[i]); !backdrop)
      return specError(spec, "/backgrounds/" + std::to_string(i), backdrop.error().message);
  if (auto quality = app::qualityOption(spec.quality); !quality) return specError(spec, "/quality", quality.error().message);
  return {};
}

}  // namespace

std::filesystem::path modelFile(const DatasetSpec& spec, size_t i) {
  if (spec.models[i] == kBuiltInModel) return {};
  const std::filesystem::path file(spec.models[i]);
  return file.is_absolute() ? file : spec.baseDir / file;
}

std::string modelLabel(const DatasetSpec& spec, size_t i) {
  if (spec.models[i] == kBuiltInModel) return kBuiltInModel;
  return std::filesystem::path(spec.models[i]).stem().string();
}

eng::Result<DatasetSpec> parseDatasetSpec(std::string_view json, const std::string& source,
                                          const std::filesystem::path& baseDir) {
  auto document = facial::parseJsonText(json, source);
  if (!document) return document.error();
  DatasetSpec spec;
  spec.source = source;
  spec.baseDir = baseDir;
  const JsonNode root(*document, "");
  if (!root.isObject()) return eng::makeError(eng::ErrorKind::Malformed, source + ": a dataset spec is a JSON object");
  if (auto read = readFields(spec, root); !read) return read.error().prefixed(source + ": ");
  return spec;
}

eng::Result<DatasetSpec> readDatasetSpec(const std::filesystem::path& path) {
  auto bytes = eng::readFileBytes(path, facial::kMaxJsonFileBytes);
  if (!bytes) return bytes.error();
  const std::string_view text(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  return parseDatasetSpec(text, path.string(), path.parent_path());
}

eng::Result<void> checkDatasetSpec(const DatasetSpec& spec, const std::filesystem::path& expressionsFile) {
  ENG_TRY(checkNumbers(spec));
  return checkNames(spec, expressionsFile);
}

std::string canonicalEmotionName(std::string_view name) {
  std::string out;
  for (char c : name) out += (c == ' ' || c == '-') ? '_' : char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

eng::Result<Range> parseRange(std::string_view text, std::string_view option) {
  auto number = [](std::string_view part) -> std::optional<float> {
    float value = 0.0f;
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (ec != std::errc() || ptr != part.data() + part.size() || part.empty() || !std::isfinite(value)) return std::nullopt;
    return value;
  };
  const size_t colon = text.find(':');
  auto min = number(text.substr(0, colon));
  auto max = colon == std::string_view::npos ? min : number(text.substr(colon + 1));
  if (!min || !max)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::string(option) + ": '" + std::string(text) + "' is not MIN:MAX or one number");
  return Range{*min, *max};
}

std::string canonicalSpecJson(const DatasetSpec& spec) {
  auto range = [](Range r) { return nlohmann::json::array({r.min, r.max}); };
  nlohmann::json j{{"count", spec.count}, {"seed", spec.seed}, {"width", spec.width}, {"height", spec.height},
                   {"models", spec.models}, {"emotions", spec.emotions}, {"intensity", range(spec.intensity)},
                   {"auMix", {{"probability", spec.auMix.probability}, {"units", {spec.auMix.minUnits, spec.auMix.maxUnits}},
                              {"weight", range(spec.auMix.weight)}}},
                   {"yaw", range(spec.yaw)}, {"pitch", range(spec.pitch)}, {"zoom", range(spec.zoom)},
                   {"lights", spec.lights}, {"backgrounds", spec.backgrounds}, {"quality", spec.quality}};
  return j.dump();
}

uint64_t textHash(std::string_view text) {
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

uint64_t specHash(const DatasetSpec& spec) { return textHash(canonicalSpecJson(spec)); }

std::string hashText(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace dataset
