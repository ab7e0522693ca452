#pragma once
// Emotion expressions as data: each preset is a weighted combination of FACS
// action units (Ekman & Friesen's EMFACS prototypes for the basic emotions,
// Du, Tao & Martinez 2014 for compounds) plus an emotion-level drive for rigs
// whose controls are whole expressions (VRM). Loaded from a versioned JSON file
// (data/expressions.json):
//
//   {"version": 1,
//    "expressions": {
//      "happy": {"facs": "6+12+25", "description": "...",
//                "actionUnits": {"AU6_CheekRaiser": 0.75, "AU12_LipCornerPuller_L": 1.0, ...},
//                "emotions": {"happy": 1.0}},
//      "happily_surprised": {"components": ["happy", "surprise"], "actionUnits": {...},
//                            "emotions": {"happy": 0.65, "surprise": 0.65}}}}
//
// Keys: actionUnits = channel names of actionUnits(), weights in [0,1];
// emotions = names of emotionNames(), weights in [0,1] (absent: 1 on the
// preset's own name when it is an emotion, else an equal share over the
// components); components = two or more basic emotions (makes it a compound);
// facs, description = free text. Unknown keys are errors (typos must not
// silently drop a unit).
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "engine/core/name_index.h"
#include "engine/core/result.h"
#include "facial/runtime/rig/emotions.h"

namespace facial {

struct ActionUnitWeight {
  uint32_t channel = 0;  // index into actionUnits()
  float weight = 0.0f;   // [0,1]
};

struct ExpressionPreset {
  std::string name;
  std::string facs;         // FACS formula as cited ("1+2+5B+26"), informational
  std::string description;  // informational
  std::vector<Emotion> components;            // compound: the basic emotions it combines
  std::vector<ActionUnitWeight> actionUnits;  // sparse, ascending channel order
  std::array<float, kEmotionCount> emotions{};

  bool isCompound() const { return !components.empty(); }
  // Weight of one AU channel (0 when the preset does not use it).
  float actionUnitWeight(uint32_t channel) const;
};

class ExpressionLibrary {
 public:
  // Errors name the file, the JSON path and the problem (unknown AU name,
  // non-number or non-finite weight, weight outside [0,1], bad version, ...).
  static eng::Result<ExpressionLibrary> load(const std::filesystem::path& path);
  // Same rules for JSON text that came from `source` (used in messages).
  static eng::Result<ExpressionLibrary> parse(std::string_view json, std::string_view source);

  const ExpressionPreset* find(std::string_view name) const;
  std::span<const ExpressionPreset> presets() const { return presets_; }
  // Preset names in file order.
  std::vector<std::string_view> names() const;
  // False for unknown names.
  bool isCompound(std::string_view name) const;
  size_t size() const { return presets_.size(); }

  // Writes every AU channel: clamp(preset weight * intensity, 0, 1); channels
  // the preset does not name get 0. auWeights.size() must be actionUnits().size()
  // and intensity finite, else an error naming them (nothing written).
  static eng::Result<void> evaluate(const ExpressionPreset& preset, float intensity, std::span<float> auWeights);
  // The same for the emotion channels (emotionWeights.size() == kEmotionCount).
  static eng::Result<void> evaluateEmotions(const ExpressionPreset& preset, float intensity,
                                            std::span<float> emotionWeights);

 private:
  static eng::Result<ExpressionLibrary> fromJson(const nlohmann::ordered_json& root, std::string_view source);

  std::vector<ExpressionPreset> presets_;
  eng::NameIndex index_;  // find() in one look-up: a graph names a preset per pose node
};

}  // namespace facial
