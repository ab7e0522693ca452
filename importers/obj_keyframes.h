#pragma once
// Keyframe (blend shape) sets exported as OBJ files -- neutral.obj plus one
// OBJ per expression -- turned into one glTF-ready eng::Model: the neutral mesh
// with one morph target per file (position and normal differences).
//
// A glTF vertex is a unique (v, vt, vn) corner of the NEUTRAL mesh; targets
// are mapped through the same corners, so UV seams and hard edges survive.
// Faces are grouped into one primitive per material; n-gons are fanned.
// Sparse storage of targets that move few vertices happens in saveModel.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "importers/obj_mesh.h"

namespace importers {

struct ObjTargetFile {
  std::string name;  // morph target name (unique, non-empty)
  std::filesystem::path path;
};

struct ObjKeyframeOptions {
  // Pair re-ordered vertices by position (then across shared edges)
  // instead of requiring identical vertex and face order.
  bool matchByPosition = false;
  // Distance at which two vertices coincide, as a fraction of the neutral's
  // bounding-box diagonal; at most kMaxRelativeTolerance.
  float relativeTolerance = 1e-5f;
};

// Beyond 1% of the model's size, distinct vertices (a lip and the one below
// it) would "coincide" and be matched wrongly: such a tolerance is refused.
inline constexpr float kMaxRelativeTolerance = 1e-2f;

struct ObjTargetReport {
  std::string name;
  size_t movedVertices = 0;      // glTF vertices with a non-zero position delta
  size_t unmatchedVertices = 0;  // --match-by-position: neutral vertices without a partner (delta 0)
};

struct ObjKeyframeImport {
  eng::Model model;
  std::vector<ObjTargetReport> targets;
};

// `neutralBytes`: the neutral file's content when already read (empty: read from `neutral`).
eng::Result<ObjKeyframeImport> importObjKeyframes(const std::filesystem::path& neutral, std::span<const ObjTargetFile> targets,
                                             const ObjKeyframeOptions& options = {},
                                             std::span<const uint8_t> neutralBytes = {});

// A face without targets from a polygon mesh another reader made (a PLY
// scan, importers/ply_mesh.h): built as an OBJ's neutral is.
eng::Result<eng::Model> modelFromPolygonMesh(const ObjPolygonMesh& mesh, const std::filesystem::path& path);

struct ObjKeyframeFolder {
  std::filesystem::path neutral;
  std::vector<ObjTargetFile> targets;  // sorted by name
};

// DIR/neutral.obj plus every other *.obj in DIR, each a target named after its file.
eng::Result<ObjKeyframeFolder> findObjKeyframeFolder(const std::filesystem::path& dir);

}  // namespace importers
