#pragma once
// Poses a face from a timeline document: each track's channel is a rig input
// (an action unit like "AU12_LipCornerPuller_L" or an emotion) mapped through
// the model's RigMapping, or one of the model's own morph target names
// written directly. An emotion the rig binds to no target (an action-unit
// face such as the built-in head) is played as its expression preset's action
// units at the track's value, so keying "happy" shows happy on every face.
// Sized at construction; pose() does not allocate.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "editor/timeline_document.h"
#include "engine/core/result.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace editor {

class TimelinePose {
 public:
  // rig must outlive this; baseWeights: the model's defaults (targets nothing drives).
  // expressions: the presets unbound emotions are played through (none: such emotions do nothing).
  TimelinePose(const facial::RigMapping& rig, std::span<const float> baseWeights,
               const facial::ExpressionLibrary* expressions = nullptr);

  // Every channel a track may use: the rig inputs, then the model's target names.
  std::span<const std::string> channelNames() const { return channelNames_; }
  bool knowsChannel(std::string_view channel) const;

  // targets = base weights, rig inputs of the tracks applied, then target-named
  // tracks written; muted tracks (and others while one is soloed) are left out. Tracks on unknown channels are skipped and counted in
  // unknownTracks(). Fails on a size mismatch (naming sizes).
  eng::Result<void> pose(const TimelineDocument& document, float time, std::span<float> targets);
  size_t unknownTracks() const { return unknownTracks_; }
  // The rig's expression weights of the last pose() when it has an expression
  // stage (VRM material binds, app::FaceMaterials); empty otherwise.
  std::span<const float> expressionWeights() const { return expressionWeights_; }

 private:
  const facial::RigMapping* rig_;
  std::vector<float> base_;
  std::vector<std::string> channelNames_;
  std::vector<float> actionUnits_;
  std::vector<float> emotions_;
  // Per emotion: the action units it is played as (empty when the rig binds it, or it has none).
  std::vector<std::vector<facial::ActionUnitWeight>> emotionUnits_;
  std::vector<float> expressionWeights_;
  size_t unknownTracks_ = 0;
};

}  // namespace editor
