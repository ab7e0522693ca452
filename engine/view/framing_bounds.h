#pragma once
// Bounds to frame a morphing model by, in world space. They include every
// morph target at full weight, so shapes that morph far out (SimpleMorph)
// stay in view, and they do not change with the weights, so the camera stays
// put while a face animates or across renders of several expressions.
//
// Two framings:
//  - All:  the whole model (rest pose plus every target).
//  - Face: the head and neck. Most faces users bring are full-body avatars
//    (Ready Player Me, VRoid, Mixamo): framing all of one leaves the face a
//    few pixels tall. The face is where the morph targets move vertices; the
//    head is the part of the model around it (hair cap, ears, neck stump).
//    A skinned model's head is what its head joint moves (engine/scene/
//    posed_bounds.h), in the rest pose, with the neck below it. A model with
//    neither falls back to All.
#include <optional>
#include <string_view>

#include "engine/core/enum_names.h"
#include "engine/scene/model.h"

namespace eng {

enum class FramingMode { Face, All };

inline constexpr EnumName<FramingMode> kFramingModeNames[] = {{FramingMode::Face, "face"}, {FramingMode::All, "all"}};
std::string_view framingModeName(FramingMode mode);
std::optional<FramingMode> framingModeFromName(std::string_view name);

Aabb framingBounds(const Model& model, FramingMode mode = FramingMode::All);

// The world-space box of the vertices that some morph target moves (rest and
// fully morphed positions); invalid when no target moves anything.
Aabb morphedRegionBounds(const Model& model);

// The face's features, for keeping them in view: where the morph targets move
// vertices (a skinned model posed at rest). Invalid when nothing morphs.
Aabb faceFeatureBounds(const Model& model);

// The largest zoom, at most `wanted` and at least 1, at which a camera framed
// on `framed` (OrbitCamera::frame with this aspect and field of view) still
// shows all of `shown` from the front. A face view zooms past the head's
// bounds to fill the image with the face; on a head whose features fill it
// (a robot's eyes reaching its sides) that zoom would cut them off.
float zoomShowing(const Aabb& framed, const Aabb& shown, float wanted, float aspect, float fovYDegrees = 30.0f);

}  // namespace eng
