#pragma once
// A stylised ear: a closed, flattened shell with a raised rim (helix), a
// bowl (concha) and a lobe, set against the side of the skull. It does not
// deform with any action unit.
#include "bake/head/part_mesh.h"

namespace bake {

// side: +1 left ear (+X), -1 right ear.
PartMesh buildEar(float side);

}  // namespace bake
