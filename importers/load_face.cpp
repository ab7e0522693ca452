#include "importers/load_face.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "engine/core/log.h"
#include "engine/core/text_lines.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "facial/runtime/graph/weight_range.h"
#include "importers/candide_import.h"
#include "importers/face_dressing.h"
#include "importers/fbx_document.h"
#include "importers/fbx_scene.h"
#include "importers/loop_subdivision.h"
#include "importers/obj_keyframes.h"
#include "importers/ply_mesh.h"
#include "importers/stl_mesh.h"
#include "importers/vrm_import.h"

namespace importers {

bool isPlainMesh(FaceFormat format) {
  return format == FaceFormat::Gltf || format == FaceFormat::Obj || format == FaceFormat::Ply || format == FaceFormat::Fbx ||
         format == FaceFormat::Stl;
}

std::string_view faceFormatName(FaceFormat format) {
  switch (format) {
    case FaceFormat::Gltf: return "glTF";
    case FaceFormat::Vrm: return "VRM";
    case FaceFormat::ObjSet: return "OBJ keyframe set";
    case FaceFormat::Candide3: return "CANDIDE-3";
    case FaceFormat::Obj: return "OBJ";
    case FaceFormat::Ply: return "PLY";
    case FaceFormat::Fbx: return "FBX";
    case FaceFormat::Stl: return "STL";
  }
  return "?";
}

namespace {

// Enough of the file to tell the formats apart.
constexpr size_t kSniffBytes = 64;

std::string shapeKey(std::string_view name) {
  std::string key;
  for (char c : name) key += (c == ' ' || c == '-') ? '_' : char(std::tolower(static_cast<unsigned char>(c)));
  if (key.compare(0, 3, "su_") == 0) key.erase(0, 3);
  return key;
}

eng::Result<LoadedFace> loadObjSet(const std::filesystem::path& dir) {
  auto folder = findObjKeyframeFolder(dir);
  if (!folder) return folder.error();
  auto imported = importObjKeyframes(folder->neutral, folder->targets);
  if (!imported) return imported.error();
  LoadedFace face{std::move(imported->model), FaceFormat::ObjSet, nullptr, std::nullopt};
  face.model.sourcePath = dir.string();
  return face;
}

// An OBJ file: its first line that is not blank or a comment starts with an
// OBJ statement (exporters open with comment lines: a few kilobytes are read).
bool looksLikeObj(std::span<const uint8_t> bytes) {
  eng::TextLines lines(std::string_view(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 4096)));
  std::string_view line;
  while (lines.nextNonBlank(line)) {
    if (line[0] == '#') continue;
    const std::string_view word = line.substr(0, line.find_first_of(" \t"));
    for (std::string_view statement : {"v", "vt", "vn", "f", "o", "g", "s", "mtllib", "usemtl"})
      if (word == statement) return true;
    return false;
  }
  return false;
}

// A scan read into polygons by `read` (PLY, STL), built as one OBJ file is.
template <typename Read>
eng::Result<LoadedFace> loadScan(std::span<const uint8_t> bytes, const std::filesystem::path& path, FaceFormat format, Read read) {
  auto mesh = read(bytes, path);
  if (!mesh) return mesh.error();
  auto model = modelFromPolygonMesh(*mesh, path);
  if (!model) return model.error();
  model->sourcePath = path.string();
  return LoadedFace{std::move(*model), format, nullptr, std::nullopt};
}

eng::Result<LoadedFace> loadFbx(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  auto model = importFbx(bytes, path);
  if (!model) return model.error();
  return LoadedFace{std::move(*model), FaceFormat::Fbx, nullptr, std::nullopt};
}

eng::Result<LoadedFace> loadObjMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  auto imported = importObjKeyframes(path, {}, {}, bytes);
  if (!imported) return imported.error();
  LoadedFace face{std::move(imported->model), FaceFormat::Obj, nullptr, std::nullopt};
  face.model.sourcePath = path.string();
  return face;
}

// VRM 0.x avatars face -Z (Unity's convention), glTF and VRM 1.0 faces +Z:
// the scene turns half a turn about +Y under a new root, as three-vrm's
// rotateVRM0 does, so the camera meets the face. Skinned meshes follow
// (their joints are under the new root).
void faceForward(eng::Model& model) {
  eng::Node turn;
  turn.name = "VRM 0.x faces +Z";
  turn.rotation = glm::angleAxis(glm::pi<float>(), glm::vec3(0.0f, 1.0f, 0.0f));
  turn.children = model.roots;
  const int index = int(model.nodes.size());
  for (int root : model.roots) model.nodes[size_t(root)].parent = index;
  model.nodes.push_back(std::move(turn));
  model.roots = {index};
}

// `facial info` lists each extension with what was done with it; the glTF
// loader knows nothing of VRM's, so say here what the VRM importer read.
void describeVrmExtensions(const facial::VrmExpressionSet& set, eng::Model& model) {
  const char* used = set.specVersion == 0 ? "VRM" : "VRMC_vrm";
  const size_t binds = set.binds.size() + set.materialColorBinds.size() + set.textureTransformBinds.size();
  for (eng::ExtensionUse& e : model.extensions) {
    if (e.name == used)
      e.outcome = "applied: " + std::to_string(set.expressions.size()) + " expressions (" + std::to_string(binds) +
                  " bind(s)), lookAt (" + (set.lookAt.type == facial::VrmLookAtType::Bone ? "bone" : "expression") + ")";
    else if (e.name == "VRM" || e.name == "VRMC_vrm")
      e.outcome = std::string("ignored: ") + used + " read instead";
  }
}

eng::Result<LoadedFace> loadGltfOrVrm(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  auto model = eng::loadModelFromBytes(bytes, path);
  if (!model) return model.error();
  auto vrm = findVrmExpressions(bytes, path.string());
  if (!vrm) return vrm.error();
  if (!*vrm) return LoadedFace{std::move(*model), FaceFormat::Gltf, nullptr, std::nullopt};
  // The glTF loader skips the VRM extensions it does not know; here they are read.
  std::erase_if(model->warnings, [](const std::string& w) {
    return w == "optional extension VRM ignored" || w == "optional extension VRMC_vrm ignored";
  });
  const eng::WeightLayout layout(*model);
  const facial::VrmExpressionSet& set = **vrm;
  bool sameLayout = set.meshTargetOffsets.size() == size_t(layout.meshCount()) + 1;
  for (int m = 0; sameLayout && m <= layout.meshCount(); ++m) sameLayout = set.meshTargetOffsets[m] == layout.offset(m);
  if (!sameLayout)
    return eng::makeError(eng::ErrorKind::Malformed, path.string() + ": the VRM expressions address " + std::to_string(set.targetCount()) +
                          " morph targets over " + std::to_string(set.meshTargetOffsets.size() - 1) +
                          " meshes, the loaded model has " + std::to_string(layout.total()) + " over " +
                          std::to_string(layout.meshCount()));
  if (set.specVersion == 0) faceForward(*model);
  describeVrmExtensions(set, *model);
  // What the VRM importer left out (a bind it cannot apply, ...): one line each, here and in `facial info`.
  for (const std::string& warning : set.warnings) {
    eng::logWarning(warning);
    model->warnings.push_back(warning);
  }
  return LoadedFace{std::move(*model), FaceFormat::Vrm, std::make_shared<const facial::VrmExpressionSet>(std::move(**vrm)),
                    std::nullopt};
}

eng::Result<LoadedFace> loadCandide3(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  eng::LoadBudget budget;  // one for the parse and both subdivision steps
  auto model = parseCandide3(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string(), budget);
  if (!model) return model.error();
  // 113 vertices shade and outline as facets: two Loop steps make the mask
  // (the first primitive; the others are its eyeballs) a smooth surface.
  eng::Mesh& mesh = model->meshes.front();
  for (int step = 0; step < 2; ++step)
    if (auto smooth = loopSubdivide(mesh.primitives.front(), path.string() + ": " + mesh.name, budget); !smooth) return smooth.error();
  return LoadedFace{std::move(*model), FaceFormat::Candide3, nullptr, std::nullopt};
}

// What every format shares once imported: the shapes, then the display copy.
eng::Result<LoadedFace> finish(eng::Result<LoadedFace> face, const std::filesystem::path& path, const LoadFaceOptions& options) {
  if (!face) return face.error();
  if (auto baked = bakeShapes(face->model, options.shapes); !baked) return baked.error().prefixed(path.string() + ": ");
  if (options.dressForDisplay) face->dressed = dressedForDisplay(face->model);
  return face;
}

}  // namespace

eng::Result<LoadedFace> loadFace(const std::filesystem::path& path, const LoadFaceOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return finish(loadObjSet(path), path, options);
  auto bytes = eng::readFileBytes(path, eng::GltfLoadLimits{}.maxFileBytes);
  if (!bytes) return bytes.error();
  return loadFaceFromBytes(*bytes, path, options);
}

eng::Result<LoadedFace> loadFaceFromBytes(std::span<const uint8_t> bytes, const std::filesystem::path& path,
                                          const LoadFaceOptions& options) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min(bytes.size(), kSniffBytes));
  const size_t first = text.find_first_not_of(" \t\r\n");
  const std::string_view start = first == std::string_view::npos ? std::string_view() : text.substr(first);
  if (start.starts_with("glTF") || start.starts_with("{")) return finish(loadGltfOrVrm(bytes, path), path, options);
  if (start.starts_with("# VERTEX LIST")) return finish(loadCandide3(bytes, path), path, options);
  // Its .mtl and textures are read beside `path`.
  if (looksLikeObj(bytes)) return finish(loadObjMesh(bytes, path), path, options);
  if (looksLikePly(bytes)) return finish(loadScan(bytes, path, FaceFormat::Ply, readPlyPolygonMesh), path, options);
  if (fbx::looksLikeFbx(bytes)) return finish(loadFbx(bytes, path), path, options);
  if (looksLikeStl(bytes)) return finish(loadScan(bytes, path, FaceFormat::Stl, readStlPolygonMesh), path, options);
  return eng::makeError(eng::ErrorKind::Unsupported, path.string() + ": not a face this program reads (glTF / GLB, VRM, FBX, a folder of "
                        "OBJ keyframes, an OBJ, a PLY, an STL or a CANDIDE-3 .wfm); the file starts with neither 'glTF', '{', "
                        "'Kaydara FBX', '; FBX', '# VERTEX LIST', 'ply', 'solid' nor an OBJ statement, and is no binary STL "
                        "(84 bytes and 50 per triangle)");
}

eng::Result<void> bakeShapes(eng::Model& model, std::span<const std::string> shapes) {
  for (const std::string& assignment : shapes) {
    const facial::NamedWeight shape = ENG_TRY_VALUE(facial::parseNamedWeight(assignment, "--shape"));
    const std::string& name = shape.name;
    const float value = shape.value;
    // Exact names first, then the loose spelling.
    int matched = 0;
    for (bool loose : {false, true}) {
      for (eng::Mesh& mesh : model.meshes)
        for (size_t t = 0; t < mesh.targetNames.size(); ++t) {
          if (loose ? shapeKey(mesh.targetNames[t]) != shapeKey(name) : mesh.targetNames[t] != name) continue;
          for (eng::Primitive& prim : mesh.primitives) {
            const eng::MorphTarget& target = prim.targets[t];
            for (size_t v = 0; v < target.positions.size(); ++v) prim.positions[v] += value * target.positions[v];
            for (size_t v = 0; v < target.normals.size(); ++v) {
              const glm::vec3 n = prim.normals[v] + value * target.normals[v];
              if (glm::length(n) > 1e-6f) prim.normals[v] = glm::normalize(n);
            }
          }
          mesh.defaultWeights[t] = 0.0f;
          ++matched;
        }
      if (matched > 0) break;
    }
    if (matched == 0) {
      std::vector<std::string> candidates;
      for (const eng::Mesh& mesh : model.meshes)
        for (const std::string& t : mesh.targetNames)
          if (t.compare(0, 3, "SU_") == 0) candidates.push_back(t);
      if (candidates.empty())
        for (const eng::Mesh& mesh : model.meshes) candidates.insert(candidates.end(), mesh.targetNames.begin(), mesh.targetNames.end());
      std::string list;
      for (size_t i = 0; i < candidates.size() && i < 12; ++i) list += (i ? ", " : "") + candidates[i];
      if (candidates.size() > 12) list += ", ... (" + std::to_string(candidates.size()) + " in all)";
      return eng::makeError(eng::ErrorKind::NotFound, "--shape: no shape unit or morph target named '" + name + "'" +
                            (list.empty() ? std::string("; the model has none") : "; available: " + list));
    }
  }
  return {};
}

}  // namespace importers
