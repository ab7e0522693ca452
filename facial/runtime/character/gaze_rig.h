#pragma once
// Where a model's eyes are steered by morph weights, and how a gaze (per-eye
// yaw / pitch, CharacterLife::eyeGaze) becomes those weights. Found by the
// model's flat target names and, for VRM, its lookAt expressions:
//  - ARKit: the eight eyeLook{In,Out,Up,Down}{Left,Right} shapes (also _L/_R and
//    "blendShape1."-prefixed); each eye its own, full weight at kArkitLookDegrees;
//  - FACS: targets named AU61 (eyes turn left), AU62 (right), AU63 (up), AU64
//    (down), with or without a suffix ("AU61_EyesTurnLeft"); both eyes' mean,
//    full weight at kFacsLookDegrees. Left is the face's own left (+X);
//  - VRM lookAt of type expression: the lookLeft / lookRight / lookUp / lookDown
//    expressions' morph binds, through the file's range maps (VRMC_vrm 1.0
//    lookAt.rangeMap*, VRM 0.x firstPerson.lookAt*: angle / inputMaxValue *
//    outputScale); yaw and pitch are both eyes' mean, as VRM has one gaze.
// A VRM of lookAt type bone and any rig with eye joints take
// CharacterLife::eyeRotation() on the joints instead (the application poses them).
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/character/character_life.h"
#include "facial/runtime/rig/vrm_expressions.h"

namespace facial {

inline constexpr float kArkitLookDegrees = 30.0f;
inline constexpr float kFacsLookDegrees = 30.0f;

class GazeRig {
 public:
  // targetNames: the model's flat targets (eng::WeightLayout order). vrm: its
  // VRM expressions over the same targets, or null.
  static GazeRig create(std::span<const std::string> targetNames, const VrmExpressionSet* vrm = nullptr);

  bool hasArkit() const { return hasArkit_; }
  bool hasFacs() const;
  bool hasVrmExpressions() const { return vrmDirections_ > 0; }
  // Whether apply() moves any weight.
  bool drivesWeights() const { return hasArkit() || hasFacs() || hasVrmExpressions(); }
  // "ARKit eyeLook*, FACS AU61-64, VRM lookAt expressions" or "none", for reports.
  std::string describe() const;

  // Adds the gaze to every target this rig drives, clamped to [0, 1]; other
  // weights are untouched. Errors (nothing written): weights.size() is not the
  // target count the rig was made for, a non-finite angle.
  eng::Result<void> apply(EyeGaze left, EyeGaze right, std::span<float> weights) const;

 private:
  enum ArkitSlot { InLeft, OutLeft, UpLeft, DownLeft, InRight, OutRight, UpRight, DownRight, kArkitSlots };
  enum Direction { LookLeft, LookRight, LookUp, LookDown, kDirections };

  uint32_t targetCount_ = 0;
  bool hasArkit_ = false;
  std::array<uint32_t, kArkitSlots> arkit_{};
  std::array<uint32_t, kDirections> facs_{};  // UINT32_MAX: absent
  // VRM: each direction's morph binds, and its range map.
  uint32_t vrmDirections_ = 0;
  std::array<std::vector<VrmMorphBind>, kDirections> vrmBinds_;
  std::array<VrmLookAtRangeMap, kDirections> vrmRanges_;
};

}  // namespace facial
