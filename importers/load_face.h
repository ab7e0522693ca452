#pragma once
// Any face the programs open, for an embedder too: glTF / GLB, VRM, a folder
// of OBJ keyframes, one OBJ, PLY or STL file, FBX or CANDIDE-3, told apart by content (not by extension),
// with identity shapes baked in and, when asked for, dressed for display.
//
//   auto face = importers::loadFace("facecap.glb", {.dressForDisplay = true});
//   // face->model: as loaded (rig, CPU posing, export);
//   // face->displayModel(): what to upload for drawing.
//
// Each file is read once: the bytes that tell the format apart are the ones
// the importer parses (loadFaceFromBytes), and a glTF's JSON is parsed for
// VRM expressions only when it names a VRM extension.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/rig/vrm_expressions.h"

namespace importers {

// What a face file is, told by its content.
// Obj: one OBJ file, a face without targets (a scan, a sculpt), which
// autorig gives the built-in head's action units.
enum class FaceFormat : uint8_t { Gltf, Vrm, ObjSet, Candide3, Obj, Ply, Fbx, Stl };
std::string_view faceFormatName(FaceFormat format);
// A mesh as exporters and scanners write it (glTF / GLB, FBX, OBJ, PLY, STL), which
// autorig makes targets for; not a VRM, an OBJ keyframe set or CANDIDE-3,
// whose rigs come with them.
bool isPlainMesh(FaceFormat format);
// What loadFace opens, for a MODEL option's help.
inline constexpr const char* kFaceFormatsHelp = "Face: glTF / GLB, VRM, FBX, OBJ keyframe folder, OBJ, PLY, STL or CANDIDE-3 .wfm";

struct LoadFaceOptions {
  // "NAME=VALUE" identity parameters baked into the rest mesh (bakeShapes).
  std::span<const std::string> shapes;
  // Also make the copy to draw, dressed (face_dressing.h): an untextured face
  // gets procedural eyes, teeth and skin colours, painted brows and baked
  // occlusion. Off, the face is drawn as its file has it. The programs turn
  // it on; the model itself stays as loaded either way.
  bool dressForDisplay = false;
};

// A face as loaded, before any rig.
struct LoadedFace {
  // As loaded, shapes baked: what to inspect, rig, pose on the CPU and export.
  eng::Model model;
  FaceFormat format = FaceFormat::Gltf;
  std::shared_ptr<const facial::VrmExpressionSet> vrm;  // VRM only
  // With dressForDisplay, when the face needed dressing: `model` dressed.
  // Same nodes, meshes, geometry and targets; its materials (more of them),
  // images and vertex colours are the display's.
  std::optional<eng::Model> dressed;

  // What to upload for drawing: the dressed copy, else the model.
  const eng::Model& displayModel() const { return dressed ? *dressed : model; }
};

// Picks the importer by content: a folder is an OBJ keyframe set
// (neutral.obj + one OBJ per target), "glTF" magic or a JSON object is
// glTF / GLB, and VRM when it has a VRMC_vrm (1.0) or VRM (0.x) extension,
// "# VERTEX LIST" is a CANDIDE-3 .wfm (opened eyes, two Loop steps). Errors
// name the file and the problem.
eng::Result<LoadedFace> loadFace(const std::filesystem::path& path, const LoadFaceOptions& options = {});
// The same over a face file's bytes, already read (not a folder): `path`
// names it in messages, and its folder holds a .gltf's external files.
eng::Result<LoadedFace> loadFaceFromBytes(std::span<const uint8_t> bytes, const std::filesystem::path& path,
                                          const LoadFaceOptions& options = {});

// positions += value * target deltas (normals likewise, renormalised) for
// each "NAME=VALUE"; the target's default weight becomes 0 so the value is
// not applied twice. NAME matches a morph target exactly, else ignoring case,
// a "SU_" prefix and ' ' / '_' / '-' differences ("head_height" finds CANDIDE's
// "SU_Head height"). Errors: malformed assignment, unknown name (listing the
// model's shape units / targets).
eng::Result<void> bakeShapes(eng::Model& model, std::span<const std::string> shapes);

}  // namespace importers
