#pragma once
// The built-in head (data/head.glb, made by bake/head) as the transfer's
// source face. Its parts come from its own names (bake/head's layout:
// materials Skin, MouthInterior, Teeth, Tongue, Ear, Eye; meshes EyeLeft and
// EyeRight) and its 68 landmarks from a fixed iBUG layout in its front plane
// snapped onto the skin, so the source never depends on a detector's mood.
#include "autorig/target_transfer.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace autorig {

// `head` must outlive the result. Errors name what is missing: no skin
// material, an eyeball mesh, a landmark that misses the skin (with its index).
eng::Result<SourceFace> builtInSource(const eng::Model& head);

}  // namespace autorig
