#pragma once
// Rig decoding for whole-expression rigs: a rig for graphs that speak action
// units. The animation graph blends presets as action-unit vectors, so a
// target bound to an emotion ("target `happy` IS the happy emotion", a rig
// map's emotion key or the Expressions scheme) would never move under a graph.
// Each emotion's binding is therefore also reached from the action units
// through the least-squares decoding of the basic presets: with P the (action
// units x emotions) matrix of the six basic presets at intensity 1, the emotion
// weights of an AU vector a are e = (P^T P)^-1 P^T a. This is exact for any
// linear mix of basic presets (a preset at intensity s gives s on its own
// emotion and 0 on the others; a cosine-eased transition gives the same easing
// on the two targets), and action units no preset uses (AU45 blink) leak into
// no emotion. Neutral has no action units and cannot be decoded: a neutral
// binding stays emotion-only (noted in the report).
#include "engine/core/result.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

// `rig` itself when it binds no emotion; else its AU rows as they are plus
// every emotion binding re-expressed over action units. Fails when a basic
// preset is missing or the presets are linearly dependent.
eng::Result<RigMapping> actionUnitRig(const RigMapping& rig, const ExpressionLibrary& presets);

}  // namespace facial
