#pragma once
// An untextured face whose eyeballs, teeth or tongue are in its skin's
// primitive (a scan or sculpt merged into one mesh: an STL, one OBJ object)
// is drawn all in one colour: blank eyes, skin-coloured teeth. The parts the
// rig found (face_parts.h) are given primitives of their own, each with a
// material named for it ("Eyeball", "Teeth", "Tongue"), so that the display
// dresses them as it does a face delivered in parts (importers/face_dressing.h).
#include <cstddef>

#include "autorig/face_parts.h"
#include "autorig/posed_face.h"
#include "engine/scene/model.h"

namespace autorig {

// Splits, in `model` (the face `posed` and `parts` describe, targets made or
// not), every untextured primitive that holds skin and an eyeball, the teeth
// or the tongue; the skin keeps the primitive, the others are appended to its
// mesh with every attribute and target carried. Returns how many primitives
// were added.
size_t separateInnerParts(eng::Model& model, const PosedFace& posed, const FaceParts& parts);

}  // namespace autorig
