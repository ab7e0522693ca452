#pragma once
// The tongue: a flattened ellipsoid resting inside the lower tooth arch.
#include "bake/head/part_mesh.h"

namespace bake {

PartMesh buildTongue(const glm::vec3& seamCentre);

}  // namespace bake
