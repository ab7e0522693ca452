#pragma once
// A Stanford PLY (the scan format: MeshLab, photogrammetry and structured-
// light scanners; ASCII, binary little- or big-endian), read into the polygon
// form the OBJ importer builds faces from: positions, per-vertex normals,
// texture coordinates (per vertex, or MeshLab's per-corner `texcoord`) and
// colours, and the texture MeshLab names in a `comment TextureFile` line.
#include <filesystem>
#include <span>

#include "engine/core/result.h"
#include "importers/obj_mesh.h"

namespace importers {

// Whether `bytes` open as a PLY file does: "ply" on the first line.
bool looksLikePly(std::span<const uint8_t> bytes);

// `path` names the file in messages and places its texture (confined to its
// folder: a texture named outside it is a warning, as with an OBJ's map_Kd).
// A corner indexes its vertex's position and normal (ObjCorner v = vn) and
// its texture coordinate (the vertex's, or its own per-corner one), -1 where
// the file has none.
eng::Result<ObjPolygonMesh> readPlyPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path);

}  // namespace importers
