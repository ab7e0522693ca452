#pragma once
// Vertices that are copies of one another in every attribute (position,
// normal, UVs, tangent, colour, skin, every morph target's deltas) merged
// into one, the triangles unchanged. A triangle soup (each corner its own
// vertex: three.js writes a non-indexed geometry so, an OBJ it read for
// one) then has edges: what walks the surface along them (the autorig's lip
// and lid labels, its mending of torn edges) sees one skin instead of
// thousands of loose triangles. Copies that differ in any attribute (a UV
// seam, a hard edge) stay apart; vertices no triangle uses are kept.
#include <cstddef>

#include "engine/scene/model.h"

namespace eng {

// The number of vertices removed (0: nothing changed).
size_t weldIdenticalVertices(Primitive& primitive);
size_t weldIdenticalVertices(Model& model);

}  // namespace eng
