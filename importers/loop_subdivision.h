#pragma once
// One step of Loop subdivision (C. Loop, "Smooth Subdivision Surfaces Based on
// Triangles", 1987) for low-polygon faces such as the 113-vertex CANDIDE-3
// mask: every triangle becomes four and the surface is smoothed, so the mask
// shades and outlines like a face instead of a faceted shell.
//
// Loop's rules are linear in the vertex positions, so the same weights move
// every morph target's position deltas: a subdivided target is exactly the
// subdivision of (base + delta) minus the subdivided base. Boundary edges
// (the mask's outline, eye and mouth openings) follow the boundary rules
// (midpoints; boundary vertices 3/4 own + 1/8 each boundary neighbour);
// vertices on non-manifold edges or with other than two boundary neighbours
// stay put. Texture coordinates are interpolated linearly (midpoints).
// Normals and morph normal deltas are recomputed smooth afterwards; tangents
// are dropped.
#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace importers {

// Errors: indices not a triangle list or out of range (names the primitive as `what`).
eng::Result<void> loopSubdivide(eng::Primitive& primitive, std::string_view what);
// The same, charging the vertices, triangles and target deltas it adds to the
// load's `budget` before making them (each step multiplies them by about four).
eng::Result<void> loopSubdivide(eng::Primitive& primitive, std::string_view what, eng::LoadBudget& budget);

}  // namespace importers
