#pragma once
// Bounds to frame a morphing model by: the rest pose plus every morph target
// at full weight, in world space. Unlike Model::bounds() (rest pose only) it
// keeps shapes that morph far out (SimpleMorph) in view, and unlike the bounds
// of the current pose it does not change with the weights, so the camera
// stays put while a face animates or across renders of several expressions.
#include "engine/scene/model.h"

namespace eng::vk {

Aabb framingBounds(const Model& model);

}  // namespace eng::vk
