#pragma once
// Drives ANY face with one emotion vocabulary: a RigMapping expresses every
// input channel (the FACS action units of actionUnits(), then the emotions of
// emotionNames()) as a sparse list of (target index, gain) over one model's
// flat target-name list, so apply() is a sparse matrix-vector product over
// flat arrays with no allocation.
//
// Schemes, detected from the target names (buildRigMapping):
//   ActionUnits  targets named after the channels ("AU12_LipCornerPuller_L") or
//                FACS-numbered ("AU12", "AU12_L", "au04"): identity by number/side
//   Candide3     CANDIDE-3 animation units as imported by facial_bake
//                ("AU9 Nose wrinkler"), signed weights (the mask has no lip
//                corner puller: a smile is a negative lip corner depressor)
//   Arkit52      Apple ARKit's 52 blend shapes, "eyeBlinkLeft" or "eyeBlink_L"
//                spelling (any prefix before '.' ignored), via a FACS table
//   Expressions  whole-expression controls: VRM 1.0 / 0.x expressions (happy/joy,
//                sad/sorrow, angry, surprised, neutral, blink...) or any targets
//                named after emotions ("Angry", "Sad"); driven by the emotion
//                channels, blink by AU45
//   Custom       a JSON rig map (rigmap_file.h), data/rigmaps/<model>.json
// Targets no input drives and inputs that drive nothing are reported in
// report(), never dropped silently.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/rig/emotions.h"

namespace facial {

enum class RigScheme : uint8_t { ActionUnits, Candide3, Arkit52, Expressions, Custom };
std::string_view rigSchemeName(RigScheme scheme);

// The input layout shared by every mapping: action-unit channels, then emotions.
uint32_t rigInputCount();
uint32_t emotionInput(Emotion emotion);
std::string_view rigInputName(uint32_t input);
// AU channel name or emotion name -> input index.
std::optional<uint32_t> rigInputIndex(std::string_view name);

struct RigMappingReport {
  RigScheme scheme = RigScheme::ActionUnits;
  std::string detail;                        // how the scheme was recognised, e.g. "52 of 52 ARKit names (_L/_R spelling)"
  std::vector<std::string> unmappedTargets;  // model targets that no input drives
  std::vector<std::string> unmappedInputs;   // AU / emotion channels that drive no target
  std::vector<std::string> notes;            // approximations and other decisions worth knowing
  // Several lines for logs and the CLI.
  std::string summary() const;
};

class RigMapping {
 public:
  RigScheme scheme() const { return report_.scheme; }
  const RigMappingReport& report() const { return report_; }
  size_t targetCount() const { return targetNames_.size(); }
  std::span<const std::string> targetNames() const { return targetNames_; }
  // Output weights are clamped to [minWeight, maxWeight] ([0,1] except CANDIDE's signed units).
  float minWeight() const { return minWeight_; }
  float maxWeight() const { return maxWeight_; }
  // The sparse row of one input: targets(input)[i] receives gains(input)[i] * weight.
  std::span<const uint32_t> targets(uint32_t input) const;
  std::span<const float> gains(uint32_t input) const;
  // Targets that some input drives (ascending); apply() writes only these.
  std::span<const uint32_t> drivenTargets() const { return drivenTargets_; }

  // Internal consistency (offsets, indices in range, finite gains, range).
  eng::Result<void> validate() const;

  // targetWeights[t] = clamp(sum_i w_i * gain(i, t)) for every driven target t;
  // targets no input drives are left untouched (identity shapes, lip sync of
  // another system). auWeights.size() == actionUnits().size(); emotionWeights
  // empty (all zero) or kEmotionCount; targetWeights.size() == targetCount();
  // weights finite. Otherwise an error naming the sizes / channel, nothing written.
  eng::Result<void> apply(std::span<const float> auWeights, std::span<const float> emotionWeights,
                          std::span<float> targetWeights) const;
  eng::Result<void> apply(std::span<const float> auWeights, std::span<float> targetWeights) const {
    return apply(auWeights, {}, targetWeights);
  }

 private:
  friend class RigMappingBuilder;

  RigMappingReport report_;
  std::vector<std::string> targetNames_;
  std::vector<uint32_t> offsets_;  // rigInputCount() + 1: row i is [offsets_[i], offsets_[i+1])
  std::vector<uint32_t> entryTargets_;
  std::vector<float> entryGains_;
  std::vector<uint32_t> drivenTargets_;
  float minWeight_ = 0.0f;
  float maxWeight_ = 1.0f;
};

// Collects (input, target, gain) entries in any order, then lays them out as
// flat rows and fills the report's unmapped lists.
class RigMappingBuilder {
 public:
  RigMappingBuilder(RigScheme scheme, std::span<const std::string> targetNames);

  std::span<const std::string> targetNames() const { return targetNames_; }
  // Gains of repeated (input, target) pairs add up.
  void add(uint32_t input, uint32_t target, float gain);
  void setDetail(std::string detail) { detail_ = std::move(detail); }
  void note(std::string note) { notes_.push_back(std::move(note)); }
  void setWeightRange(float minWeight, float maxWeight);

  // Fails when an entry is out of range, a gain is not finite, or the range is empty.
  eng::Result<RigMapping> build() const;

 private:
  struct Entry {
    uint32_t input;
    uint32_t target;
    float gain;
  };
  RigScheme scheme_;
  std::vector<std::string> targetNames_;
  std::vector<Entry> entries_;
  std::string detail_;
  std::vector<std::string> notes_;
  float minWeight_ = 0.0f;
  float maxWeight_ = 1.0f;
};

struct RigMappingOptions {
  std::string modelName;                  // for messages and the rig map file name
  std::filesystem::path rigmapDirectory;  // <dir>/<modelName>.json is used when it exists
  std::filesystem::path rigmapFile;       // explicit rig map; wins over detection
};

// The rig map file buildRigMapping reads for `options`: rigmapFile when
// given, else <rigmapDirectory>/<modelName>.json when it exists; empty when none.
std::filesystem::path rigMapFileFor(const RigMappingOptions& options);

// Custom rig map when one is given / found, else the first scheme the names
// match (Candide3, ActionUnits, Arkit52, Expressions). Fails, suggesting a rig
// map file, when no scheme recognises the names.
eng::Result<RigMapping> buildRigMapping(std::span<const std::string> targetNames, const RigMappingOptions& options = {});
// Forces one built-in scheme (not Custom); fails when it recognises none of the names.
eng::Result<RigMapping> buildRigMapping(std::span<const std::string> targetNames, RigScheme scheme);

}  // namespace facial
