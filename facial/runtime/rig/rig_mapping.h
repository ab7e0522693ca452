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
//                sad/sorrow, angry, surprised, relaxed/fun, neutral, blink...) or
//                any targets named after emotions ("Angry", "Sad"); driven by the
//                emotion channels, blink by AU45
//   VRoid        VRoid Studio's Fcl_ALL_* / Fcl_BRW_* / Fcl_EYE_* / Fcl_MTH_*
//                blend shapes (Fcl_ALL_Joy, Fcl_BRW_Angry, Fcl_EYE_Close_L, ...)
//   Visemes      lip-sync shapes only (Oculus / Ready Player Me viseme_sil ..
//                viseme_U): the jaw units drive the open vowel, no emotion
//   Custom       a JSON rig map (rigmap_file.h), data/rigmaps/<model>.json
// Targets no input drives and inputs that drive nothing are reported in
// report(), never dropped silently; viseme shapes (lip sync) are listed as
// visemes, not as unmapped targets.
//
// Viseme block (lip sync): besides the pose inputs (rigInputCount(): action
// units, then emotions) every mapping has a third block of 15 inputs, the
// Oculus visemes (speech/viseme.h), named "viseme_sil" .. "viseme_U"
// (rigVisemeInputName; rigVisemeIndex also reads "PP", "pp", "viseme_pp").
// They are kept apart from the pose inputs so that code laid over the pose
// layout (rig maps, calibration, the editor's timeline) is unchanged; they are
// driven by applyWithVisemes(). How each scheme realises them (speech_rig.cpp):
//   viseme_* targets (any scheme)  identity (rest also meets the lips)
//   VRM aa/ih/ou/ee/oh, 0.x a/i/u/e/o, VRoid Fcl_MTH_A..O (+ Fcl_MTH_Close)
//                                   a vowel blend per viseme (through the
//                                   expression stage: overrideMouth applies;
//                                   a vowel that binds nothing borrows one)
//   ARKit 52                        composed from the mouth shapes
//   action units, CANDIDE-3         composed through the rig's own AU rows
//   rig map "visemes" block         the targets it names per viseme or mouth
//                                   channel (rigmap_file.h); a rig map without
//                                   one gets the first realisation above its
//                                   rows and names allow
// A rig none of these reach cannot speak (speaks() false).
//
// Expression stage (VRM): a mapping built over a VRM model's expressions
// (attachExpressionStage) has rows that address expressions, not morph
// targets; apply() turns the expression weights into morph weights through
// the expressions' binds with VRM's isBinary and override rules
// (vrm_expressions.h). targetNames() are then the model's morph targets and
// controlNames() the expressions. Code that rebuilds a mapping from its rows
// (RigMappingBuilder over controlNames(), then setExpressionStage with the
// shared stage, as attachExpressionStage and facial::actionUnitRig do) keeps
// the stage; a builder over targetNames() would lose it.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/rig/emotions.h"
#include "facial/runtime/speech/viseme.h"
#include "facial/runtime/rig/vrm_expressions.h"

namespace facial {

enum class RigScheme : uint8_t { ActionUnits, Candide3, Arkit52, Expressions, VRoid, Visemes, Custom };
std::string_view rigSchemeName(RigScheme scheme);

// The input layout shared by every mapping: action-unit channels, then emotions.
uint32_t rigInputCount();
uint32_t emotionInput(Emotion emotion);
std::string_view rigInputName(uint32_t input);
// AU channel name or emotion name -> input index.
std::optional<uint32_t> rigInputIndex(std::string_view name);
// The viseme block: "viseme_PP"; read back from "viseme_PP", "PP" or any case of either.
std::string rigVisemeInputName(Viseme viseme);
std::optional<Viseme> rigVisemeIndex(std::string_view name);

struct RigMappingReport {
  RigScheme scheme = RigScheme::ActionUnits;
  std::string detail;                        // how the scheme was recognised, e.g. "52 of 52 ARKit names (_L/_R spelling)"
  std::vector<std::string> unmappedTargets;  // model targets that no input drives (each name once)
  std::vector<std::string> unmappedInputs;   // AU / emotion channels that drive no target
  std::vector<std::string> notes;            // approximations and other decisions worth knowing
  std::vector<std::string> visemes;          // lip-sync shapes / expressions of the model (each name once)
  std::string speech;                        // how the viseme block is realised ("" when the rig cannot speak)
  // How each emotion channel is realised when the rig binds emotions
  // ("happy <- 'joy'", "fear <- 'surprised' x0.55 + 'sad' x0.45"); empty when
  // emotions reach the face through the action units only.
  std::vector<std::string> emotions;
  std::string stage;                         // the expression stage, e.g. "VRM 1.0: 18 expressions -> 1 morph target"
  std::vector<std::string> unmappedControls; // expressions no input drives (expression stage only)
  // Several lines for logs and the CLI.
  std::string summary() const;
};

class RigMapping {
 public:
  RigScheme scheme() const { return report_.scheme; }
  const RigMappingReport& report() const { return report_; }
  size_t targetCount() const { return targetNames_.size(); }
  std::span<const std::string> targetNames() const { return targetNames_; }
  // What the rows address: the expressions of the expression stage, else targetNames().
  std::span<const std::string> controlNames() const { return stage_ ? controlNames_ : targetNames_; }
  const VrmExpressionSet* expressionStage() const { return stage_.get(); }
  const std::shared_ptr<const VrmExpressionSet>& sharedExpressionStage() const { return stage_; }
  // Output weights are clamped to [minWeight, maxWeight] ([0,1] except CANDIDE's signed, linear units).
  float minWeight() const { return minWeight_; }
  float maxWeight() const { return maxWeight_; }
  // The sparse row of one input: control targets(input)[i] receives gains(input)[i] * weight
  // (a morph target, or an expression of the expression stage).
  std::span<const uint32_t> targets(uint32_t input) const;
  std::span<const float> gains(uint32_t input) const;
  // Targets that some input drives (ascending); apply() writes only these.
  std::span<const uint32_t> drivenTargets() const { return drivenTargets_; }
  // The viseme block's sparse rows (controls, as targets()).
  std::span<const uint32_t> visemeTargets(Viseme viseme) const;
  std::span<const float> visemeGains(Viseme viseme) const;
  // Whether any viseme drives something: the rig can speak.
  bool speaks() const { return !visemeEntryTargets_.empty(); }

  // Internal consistency (offsets, indices in range, finite gains, range).
  eng::Result<void> validate() const;

  // targetWeights[t] = clamp(sum_i w_i * gain(i, t)) for every driven target t;
  // targets no input drives are left untouched (identity shapes, lip sync of
  // another system). auWeights.size() == actionUnits().size(); emotionWeights
  // empty (all zero) or kEmotionCount; targetWeights.size() == targetCount();
  // weights finite. Otherwise an error naming the sizes / channel, nothing written.
  // With an expression stage the expression weights are clamped to [0, 1],
  // resolved by the stage and the morph weights it binds written; it uses
  // scratch inside the mapping, so one mapping must not apply() on two
  // threads at once (give each thread its own copy).
  // expressionWeights, when not empty (expression stage only, controlNames()
  // long), also receives the expression weights handed to the stage, for the
  // stage's material binds (VrmExpressionSet::applyMaterials).
  eng::Result<void> apply(std::span<const float> auWeights, std::span<const float> emotionWeights,
                          std::span<float> targetWeights, std::span<float> expressionWeights = {}) const;
  eng::Result<void> apply(std::span<const float> auWeights, std::span<float> targetWeights) const {
    return apply(auWeights, {}, targetWeights);
  }
  // apply() with the viseme block: visemeWeights empty (exactly apply()) or
  // kVisemeCount, finite. It writes the targets the visemes drive as well.
  eng::Result<void> applyWithVisemes(std::span<const float> auWeights, std::span<const float> emotionWeights,
                                     std::span<const float> visemeWeights, std::span<float> targetWeights,
                                     std::span<float> expressionWeights = {}) const;

 private:
  friend class RigMappingBuilder;
  eng::Result<void> checkInputs(std::span<const float> auWeights, std::span<const float> emotionWeights) const;
  // rows[c] = sum over inputs of weight * gain for every control c the rows reach.
  void accumulate(std::span<const float> auWeights, std::span<const float> emotionWeights,
                  std::span<const float> visemeWeights, std::span<float> rows) const;

  RigMappingReport report_;
  std::vector<std::string> targetNames_;
  std::vector<uint32_t> offsets_;  // rigInputCount() + 1: row i is [offsets_[i], offsets_[i+1])
  std::vector<uint32_t> entryTargets_;
  std::vector<float> entryGains_;
  std::vector<uint32_t> drivenTargets_;
  std::vector<uint32_t> visemeOffsets_;  // kVisemeCount + 1, as offsets_
  std::vector<uint32_t> visemeEntryTargets_;
  std::vector<float> visemeEntryGains_;
  std::vector<uint32_t> speechDrivenTargets_;  // drivenTargets_ and the targets the visemes drive (ascending)
  float minWeight_ = 0.0f;
  float maxWeight_ = 1.0f;
  std::shared_ptr<const VrmExpressionSet> stage_;
  std::vector<std::string> controlNames_;  // stage expressions (stage only)
  mutable std::vector<float> controlScratch_;
  mutable std::vector<float> stageScratch_;
};

// Collects (input, target, gain) entries in any order, then lays them out as
// flat rows and fills the report's unmapped lists.
class RigMappingBuilder {
 public:
  RigMappingBuilder(RigScheme scheme, std::span<const std::string> targetNames);
  // A builder that starts as `rig` does: its scheme, control names, detail,
  // notes, weight range, expression stage and viseme block, and its pose rows
  // unless `withRows` is false (for code that re-derives the pose rows, as
  // calibration does: the rig keeps speaking).
  // withVisemes false leaves the viseme block empty (for mapSpeech to fill again).
  static RigMappingBuilder startingFrom(const RigMapping& rig, bool withRows = true, bool withVisemes = true);

  std::span<const std::string> targetNames() const { return targetNames_; }
  const VrmExpressionSet* expressionStage() const { return stage_.get(); }
  float minWeight() const { return minWeight_; }
  // Gains of repeated (input, target) pairs add up.
  void add(uint32_t input, uint32_t target, float gain);
  void addViseme(Viseme viseme, uint32_t target, float gain);
  // The (target, gain) entries added so far for a pose input, repeats merged
  // (what a composed viseme row is made of).
  std::vector<std::pair<uint32_t, float>> row(uint32_t input) const;
  bool speaks() const { return !visemeEntries_.empty(); }
  void setSpeech(std::string speech) { speech_ = std::move(speech); }
  void setDetail(std::string detail) { detail_ = std::move(detail); }
  void note(std::string note) { notes_.push_back(std::move(note)); }
  void setWeightRange(float minWeight, float maxWeight);
  // Rows address the stage's expressions (the builder's targetNames() must be
  // their names, in order); the built mapping's targets are morphTargetNames
  // (the stage's flat target count).
  void setExpressionStage(std::shared_ptr<const VrmExpressionSet> stage, std::vector<std::string> morphTargetNames);

  // Fails when an entry is out of range, a gain is not finite, or the range is empty.
  eng::Result<RigMapping> build() const;

 private:
  struct Entry {
    uint32_t input;
    uint32_t target;
    float gain;
  };
  // The steps of build(), in order.
  eng::Result<void> checkEntries() const;
  void layOutRows(RigMapping& mapping) const;
  void layOutVisemeRows(RigMapping& mapping) const;
  void markSpeechTargets(RigMapping& mapping) const;
  bool isViseme(const std::string& name) const;
  eng::Result<void> markDrivenTargets(RigMapping& mapping) const;
  void describeEmotions(RigMapping& mapping) const;
  RigScheme scheme_;
  std::vector<std::string> targetNames_;
  std::vector<Entry> entries_;
  std::vector<Entry> visemeEntries_;  // input: the Viseme
  std::string speech_;
  std::string detail_;
  std::vector<std::string> notes_;
  float minWeight_ = 0.0f;
  float maxWeight_ = 1.0f;
  std::shared_ptr<const VrmExpressionSet> stage_;
  std::vector<std::string> morphTargetNames_;
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
// The rig of a VRM model: the mapping detected (or read from a rig map) over
// the expression names (VRM 1.0 preset / custom names, VRM 0.x presetName or
// group name), then attachExpressionStage. morphTargetNames: the model's flat
// targets (vrm->targetCount() of them). Notes list the expressions that bind
// nothing and the binds the renderer cannot show.
eng::Result<RigMapping> buildVrmRigMapping(std::shared_ptr<const VrmExpressionSet> vrm,
                                           std::span<const std::string> morphTargetNames,
                                           const RigMappingOptions& options = {});
// `rows` (built over the stage's expression names) re-laid over the stage.
eng::Result<RigMapping> attachExpressionStage(const RigMapping& rows, std::shared_ptr<const VrmExpressionSet> stage,
                                              std::span<const std::string> morphTargetNames);
// A lip-sync shape or expression: Oculus / Ready Player Me "viseme_*", VRM 1.0
// aa/ih/ou/ee/oh, VRM 0.x a/i/u/e/o, VRoid Fcl_MTH_A/I/U/E/O.
bool isVisemeName(std::string_view name);
// Fills the builder's viseme block for its scheme (see "Viseme block" above);
// leaves it empty when nothing on the rig moves the mouth.
void mapSpeech(RigMappingBuilder& builder, RigScheme scheme);
// One line for a rig that cannot speak: "<model>: cannot speak: it has nothing
// to move the mouth; none of its N targets is ...; a rig map can name ...".
std::string cannotSpeakMessage(const RigMapping& rig, std::string_view model);

// What of a face the rig's emotion inputs and action units move.
struct EmotionFeatures {
  bool emotions = false;    // an emotion input (a whole-expression target) drives something
  bool brows = false;       // AU1, AU2 or AU4
  bool lipCorners = false;  // AU12 or AU15
};
EmotionFeatures emotionFeatures(const RigMapping& rig);

// Whether the rig can show the seven emotions: an emotion input drives
// something, or the action units move both the brows and the lip corners,
// the features every basic emotion is read from (sad, surprise, fear and
// anger are first of all brows). A viseme rig (jaw and lips only), a
// lip-sync set of ARKit's mouth shapes or a blink-only one speaks or blinks
// but cannot emote: such faces are the ones worth giving action units
// (issue 33's autorig), which keeps their own shapes.
bool showsEmotions(const RigMapping& rig);

// Forces one built-in scheme (not Custom); fails when it recognises none of the names.
eng::Result<RigMapping> buildRigMapping(std::span<const std::string> targetNames, RigScheme scheme);

}  // namespace facial
