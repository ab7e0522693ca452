#pragma once
// What a labelled dataset holds, read from a spec file (data/datasets/example.json):
//
//   {"format": "facial-dataset-spec", "version": 1,
//    "count": 200, "seed": 7, "size": "256x256",
//    "models": ["head"],                     // "head": the built-in head; else files, relative to the spec
//    "emotions": ["neutral", "happy", "happily surprised"],  // presets of data/expressions.json
//    "intensity": [0.4, 1.0],                // ranges are [min, max]; a number is a fixed value
//    "auMix": {"probability": 0.3, "units": [1, 3], "weight": [0.2, 0.7]},  // random action units on top
//    "yaw": [-30, 30], "pitch": [-15, 15], "zoom": [1.0, 1.2],
//    "lights": ["studio", "soft", "left"],   // dataset/light_rigs.h
//    "backgrounds": ["studio", "#30343a", "transparent"],
//    "quality": "balanced"}
//
// Item k's parameters depend only on the seed and k (dataset/item_params.h).
// Errors name the spec file and the field: "s.json: /yaw: min 30 is above max -30".
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace dataset {

struct Range {
  float min = 0.0f;
  float max = 0.0f;
};

struct AuMix {
  float probability = 0.0f;  // of an item getting random action units on top of its emotion
  uint32_t minUnits = 1, maxUnits = 3;
  Range weight{0.2f, 0.7f};
};

// Above this an index file and a shard's label list stop being practical on
// one disk; larger sets are several datasets.
inline constexpr uint64_t kMaxItems = 100'000'000;
inline constexpr uint32_t kMaxImageSide = 4096;
inline constexpr size_t kMaxModels = 64;
inline constexpr const char* kBuiltInModel = "head";

struct DatasetSpec {
  std::string source;  // the spec file (or "command line"), for messages
  std::filesystem::path baseDir;  // relative model paths are resolved against it
  std::vector<std::string> models{kBuiltInModel};  // "head" or paths (resolved against the spec's folder)
  std::vector<std::string> emotions{"neutral"};    // preset names, canonical (happily_surprised)
  Range intensity{1.0f, 1.0f};
  AuMix auMix;
  Range yaw, pitch;
  Range zoom{1.0f, 1.0f};
  std::vector<std::string> lights{"studio"};
  std::vector<std::string> backgrounds{"studio"};
  uint32_t width = 256, height = 256;
  uint64_t count = 0;
  uint64_t seed = 0;
  std::string quality = "balanced";
};

// The file of models[i]: empty for the built-in head, else resolved against baseDir.
std::filesystem::path modelFile(const DatasetSpec& spec, size_t i);
// A model's name in labels: "head", or the file name without extension.
std::string modelLabel(const DatasetSpec& spec, size_t i);

// Reads and checks (checkDatasetSpec) a spec file.
eng::Result<DatasetSpec> readDatasetSpec(const std::filesystem::path& path);
// The same from JSON text that came from `source`; relative model paths are
// resolved against `baseDir`.
eng::Result<DatasetSpec> parseDatasetSpec(std::string_view json, const std::string& source,
                                          const std::filesystem::path& baseDir);

// Every field in range, every name known (emotions against `expressionsFile`,
// lights, backgrounds, models that exist). Errors: "<source>: /field: problem".
eng::Result<void> checkDatasetSpec(const DatasetSpec& spec, const std::filesystem::path& expressionsFile);

// "happily surprised" / "Happily-Surprised" -> "happily_surprised".
std::string canonicalEmotionName(std::string_view name);
// "[min, max]" or a number, for flags (--yaw -30:30 or --yaw 10).
eng::Result<Range> parseRange(std::string_view text, std::string_view option);

// The spec as canonical JSON (sorted keys, no source): the same spec gives
// the same text and hash in every shard, so a folder refuses a different spec.
std::string canonicalSpecJson(const DatasetSpec& spec);
uint64_t specHash(const DatasetSpec& spec);  // textHash(canonicalSpecJson(spec))
uint64_t textHash(std::string_view text);    // FNV-1a, 64 bits
// "%016llx".
std::string hashText(uint64_t hash);

}  // namespace dataset
