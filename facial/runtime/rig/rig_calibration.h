#pragma once
// Per-rig strength calibration. ARKit shapes (and FACS targets) from
// different vendors move a face by different amounts: one vendor's
// mouthSmile lifts the lip corners a few millimetres, another's a
// centimetre, so one preset reads strong on one face and faint on the next.
// The calibration measures how far each action unit's row of the rig moves
// the face -- the largest vertex displacement of its strongest target,
// relative to the face's size -- and scales the row toward a common
// reference strength for that action unit (a fraction of the face size,
// kActionUnitReach below). Scaling is bounded both ways so a rig is nudged
// toward the reference, never rebuilt: a target is still never driven past
// the rig's weight range, so a weak shape cannot be pushed into
// extrapolation. Blinks are not calibrated (a blink must close the lid,
// whatever the shape's reach). Per-model overrides multiply on top
// (rig map "calibration": {"AU12_LipCornerPuller_L": 1.2}).
//
// Intensity semantics are unchanged: an action unit at 0 leaves the rig at
// rest, at 1 it reaches the calibrated full strength.
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

struct RigCalibrationOptions {
  float minScale = 0.6f;  // how far a too-strong row is damped
  float maxScale = 1.6f;  // how far a too-weak row is raised (then clamped by the weight range)
  // Per action unit channel, multiplied after the measured scale (rig map overrides).
  std::vector<std::pair<std::string, float>> overrides;
  // Per action unit channel, the scale a rigged file states for its own
  // targets, taken instead of the measured one (overrides still multiply).
  // A face rigged by `facial autorig` states the built-in head's: its units
  // move each feature as far as the head's for the face's own proportions,
  // and measured against the face's size they were driven unlike the head's
  // (Ready Player Me's outer brows x1.37 where the head's are x0.93).
  std::vector<std::pair<std::string, float>> given;
};

struct ActionUnitCalibration {
  std::string channel;
  float reach = 0.0f;      // measured: largest displacement of the row at 1, / face size
  float reference = 0.0f;  // wanted reach, / face size
  float scale = 1.0f;      // applied to the row's gains
};

struct RigCalibration {
  RigMapping rig;
  std::vector<ActionUnitCalibration> units;  // every calibrated channel that drives a target
  std::string summary() const;               // a line per channel
};

// The reference reach of an action unit channel (fraction of face size), 0 for
// channels that are not calibrated (blinks).
float referenceReach(std::string_view channel);

// targetReach[t]: the largest displacement of target t at weight 1 divided by
// the face size (targetReach.size() == rig.targetCount(), finite, >= 0).
// Emotion rows (whole-expression targets) and rigs with an expression stage
// (VRM: rows drive the author's expressions) are left as they are. Errors name
// the sizes or the override that matches no channel.
eng::Result<RigCalibration> calibrateRig(const RigMapping& rig, std::span<const float> targetReach,
                                         const RigCalibrationOptions& options = {});

}  // namespace facial
