#pragma once
// A Wavefront OBJ as polygons (not yet triangulated), read with
// tinyobjloader: the form the keyframe importer compares topology on.
// OBJ indexes positions, texcoords and normals separately, so a face corner
// is a (v, vt, vn) triple; -1 marks an absent vt or vn.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"

namespace importers {

struct ObjCorner {
  int v = -1;
  int vt = -1;
  int vn = -1;
};

struct ObjMaterial {
  std::string name;
  glm::vec4 diffuse{1.0f};             // Kd, alpha from d
  std::filesystem::path diffuseTexture;  // map_Kd resolved beside the OBJ; empty when none or refused
};

struct ObjPolygonMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> texcoords;  // as in the file (V up)
  std::vector<glm::vec3> normals;
  // Per position, as the file gives them ('v x y z r g b', the extension
  // MeshLab and ZBrush write; display values, 0-1 or 0-255); empty when not
  // every vertex has one.
  std::vector<glm::vec3> colors;
  std::vector<uint32_t> faceStart;   // faceCount() + 1 offsets into corners
  std::vector<ObjCorner> corners;
  std::vector<int> faceMaterial;     // index into materials, -1 = none
  std::vector<ObjMaterial> materials;
  std::vector<std::string> warnings;

  size_t faceCount() const { return faceStart.empty() ? 0 : faceStart.size() - 1; }
  size_t faceSize(size_t f) const { return faceStart[f + 1] - faceStart[f]; }
  const ObjCorner& corner(size_t f, size_t k) const { return corners[faceStart[f] + k]; }
};

struct ObjReadOptions {
  bool materials = true;                     // read mtllib files (targets skip them)
  size_t maxFileBytes = size_t{1} << 30;
};

// Every index is checked against its array and every number for finiteness;
// mtllib and map_Kd paths are confined to the OBJ's folder (a refused or
// missing material file is a warning, as OBJ sets often carry stale paths).
// `bytes`: the file's content when already read (empty: read from `path`,
// which still names it and places its .mtl).
eng::Result<ObjPolygonMesh> readObjPolygonMesh(const std::filesystem::path& path, const ObjReadOptions& options = {},
                                               std::span<const uint8_t> bytes = {});

}  // namespace importers
