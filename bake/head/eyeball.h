#pragma once
// Eyeballs of the built-in head: spheres with a slight corneal bulge, gaze
// along +Z, and one shared painted texture (sclera, iris, pupil, a corneal
// highlight) laid out as azimuth x polar angle around the gaze axis.
#include "engine/scene/model.h"
#include "bake/head/eye_opening.h"
#include "bake/head/head_proportions.h"
#include "bake/head/part_mesh.h"

namespace bake {

PartMesh buildEyeball(const EyeOpening& eye, const HeadProportions& proportions);
eng::Image paintEyeTexture(const HeadProportions& proportions, int width, int height);

}  // namespace bake
