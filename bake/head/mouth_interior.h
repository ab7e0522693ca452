#pragma once
// Colour of the mouth-interior pocket: a gradient from the moist inner lip
// at the seam (v = 0) to the dark back of the mouth (v = 1).
#include "engine/scene/model.h"

namespace bake {

eng::Image paintMouthInteriorTexture(int height);

}  // namespace bake
