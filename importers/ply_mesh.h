#pragma once
// A Stanford PLY (the scan format: MeshLab, photogrammetry and structured-
// light scanners), read with Assimp into the polygon form the OBJ importer
// builds faces from: positions, per-vertex normals, texture coordinates and
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
// Every corner indexes the vertex's position, normal and texture coordinate
// alike (ObjCorner v = vt = vn), or -1 where the file has none.
eng::Result<ObjPolygonMesh> readPlyPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path);

}  // namespace importers
