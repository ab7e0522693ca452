#pragma once
// Which corner of a target OBJ feeds each corner of the neutral OBJ.
// Strict matching requires the exporter to have kept vertex and face order;
// matching by position recovers the correspondence of a re-ordered export:
// coincident vertices are paired through a spatial hash, then the pairing
// spreads across shared edges to the vertices the target moved.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "importers/obj_mesh.h"

namespace importers {

struct ObjCornerMap {
  std::vector<int32_t> targetCorner;  // per neutral corner (flat index): target corner, -1 unknown
  std::vector<int32_t> targetVertex;  // per neutral 'v': target 'v', -1 unmatched
  size_t unmatchedVertices = 0;       // neutral vertices used by faces that found no partner
};

// Same vertex count, face count and, face by face, the same 'v' indices.
// The error names the target, the counts and the first differing face.
eng::Result<ObjCornerMap> matchObjByTopology(const ObjPolygonMesh& neutral, const ObjPolygonMesh& target,
                                        const std::string& neutralName, const std::string& targetName);

// tolerance: largest distance (model units) at which two vertices coincide.
ObjCornerMap matchObjByPosition(const ObjPolygonMesh& neutral, const ObjPolygonMesh& target, float tolerance);

}  // namespace importers
