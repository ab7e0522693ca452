#pragma once
// An STL file (binary or ASCII), as 3D scanners and sculpting tools export a
// head: triangles only, no colours or texture coordinates, each triangle with
// its own three corners. Read into the polygon form the OBJ importer builds
// faces from, corners at the same position welded into one vertex so the
// scan is one surface again (smooth normals, landmarks cast onto it).
#include <filesystem>
#include <span>

#include "engine/core/result.h"
#include "importers/obj_mesh.h"

namespace importers {

// Binary: 80 header bytes, a triangle count, and exactly 50 bytes per
// triangle after it (the header may itself start with "solid", as some
// exporters write it). ASCII: "solid" and then a "facet".
bool looksLikeStl(std::span<const uint8_t> bytes);

// `path` names the file in messages. Facet normals are not read (exporters
// often write zeros): smooth normals are made from the welded surface.
eng::Result<ObjPolygonMesh> readStlPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path);

}  // namespace importers
