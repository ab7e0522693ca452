#pragma once
// Vertices that are copies of one another merged into one, the triangles
// unchanged. A triangle soup (each corner its own vertex: three.js writes a
// non-indexed geometry so, an OBJ it read for one) then has edges: what walks
// the surface along them (the autorig's lip and lid labels, its mending of
// torn edges) sees one skin instead of thousands of loose triangles.
//
// Copies that differ only in their shading (the normal and tangent of a hard
// edge; every corner of a flat-shaded face) can be merged too, for work that
// needs the shape's topology, and split again afterwards by
// restoreHardEdges(): copies whose triangles meet across an edge, walking
// one surface. Copies that differ in anything else (a UV seam, a skin, a
// target's deltas) stay apart, and so do the copies of two sheets that touch
// (a slit mouth's lips, the upper lip's underside on the lower lip's top:
// their triangles close onto each other across the edge they share, or their
// normals are back to back); vertices no triangle uses are kept.
#include <cstddef>

#include "engine/scene/model.h"

namespace eng {

struct WeldOptions {
  // Merge copies that differ in normal and tangent only (their normal becomes
  // the copies' mean) where their triangles share an edge, unless they close
  // into a crack there: each copy's normal leaning into the other's face,
  // the two further apart than this cosine allows (0.3: a valley narrower
  // than about 107 degrees). The built-in head's lips meet at 57-90 degrees;
  // a face's creases are wider.
  bool acrossHardEdges = false;
  float minNormalCosine = 0.3f;
};

// The number of vertices removed (0: nothing changed).
size_t weldIdenticalVertices(Primitive& primitive, const WeldOptions& options = {});
size_t weldIdenticalVertices(Model& model, const WeldOptions& options = {});

// Gives `welded` (a primitive welded across its hard edges, then changed by
// work that keeps the places of the vertices it keeps: targets made, lips cut)
// the shading of `original`, the primitive before the weld. Each triangle
// whose corners sit where one of `original`'s has them takes that triangle's
// corner normals and tangents; a vertex whose corners then ask for different
// ones is split into copies (every attribute and target carried), and the
// targets' normal deltas of every vertex at a hard edge are made anew from its
// own side's faces. Triangles without such a match keep their vertices'
// normals. Returns the number of vertices added.
size_t restoreHardEdges(Primitive& welded, const Primitive& original);

}  // namespace eng
