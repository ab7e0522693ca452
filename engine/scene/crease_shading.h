#pragma once
// Creases that form with an expression. When a target folds skin -- the brows
// drawn together, the nose wrinkled, the cheeks pushed up into the lids, the
// chin raised -- a real face forms furrows that catch shadow. A mesh of a few
// thousand vertices moves the surface but cannot fold it finely enough to
// shade the furrow, so at 256 px the expression loses the cues that tell
// anger from neutral or sad from fear. This is the procedural form of the
// wrinkle maps production rigs paint per blend shape: for every target, how
// much darker each vertex gets at full weight, measured from the geometry
// (where the target makes the surface more concave and where it compresses
// the skin). At run time the darkening is the weighted sum over the active
// targets, like the deltas themselves, so it follows any mix of targets.
#include <cstddef>
#include <vector>

#include "engine/scene/model.h"

namespace eng {

// Darkening per target: out[t] holds a value in [0, 1] per vertex, or is
// empty when target t darkens nothing (so targets without deltas cost
// nothing: a file of thousands of empty targets over many vertices once
// filled gigabytes with zeros). out is empty when the primitive has no
// targets or no triangles. Seams (vertices split at the same position) get
// the same value on both sides.
std::vector<std::vector<float>> bakeCreaseDarkening(const Primitive& primitive);

// True when any target of the primitive darkens any vertex noticeably.
bool hasCreases(const std::vector<std::vector<float>>& darkening);

}  // namespace eng
