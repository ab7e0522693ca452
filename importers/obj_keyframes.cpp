#include "importers/obj_keyframes.h"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "engine/core/uv_raster.h"  // srgbToLinear
#include "engine/scene/image_io.h"
#include "engine/scene/model_check.h"
#include "engine/scene/normals.h"
#include "importers/obj_correspondence.h"
#include "facial/runtime/json/json_document.h"  // formatNumber
#include "importers/obj_mesh.h"

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

struct CornerKey {
  int v, vt, vn;
  bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = static_cast<uint32_t>(k.v) * 0x9E3779B97F4A7C15ull;
    h ^= (static_cast<uint32_t>(k.vt) + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull + (h >> 29);
    h ^= (static_cast<uint32_t>(k.vn) + 0x85157AF5ull) * 0x94D049BB133111EBull + (h >> 31);
    return static_cast<size_t>(h);
  }
};

// One glTF primitive built from the neutral's faces of one material.
struct PrimitiveBuild {
  Primitive prim;
  std::vector<uint32_t> firstCorner;  // per glTF vertex: the neutral flat corner it was made from
  bool explicitNormals = true;        // every corner had a usable vn
  bool anyTexcoords = false;
  std::vector<glm::vec3> generatedNeutralNormals;  // smooth normals of the neutral (for targets without vn)
};

void normalizeOr(glm::vec3& n, bool& ok) {
  // In double: the float length of a huge (still finite) vn overflows.
  const double len = glm::length(glm::dvec3(n));
  if (std::isfinite(len) && len > 1e-12) n = glm::vec3(glm::dvec3(n) / len);
  else ok = false;
}

// The OBJ's vertex colours as linear RGBA (the file's are display values,
// in 0-1 or, from some writers, 0-255); empty when it has none.
std::vector<glm::vec4> linearColours(const ObjPolygonMesh& obj) {
  float top = 0.0f;
  for (const glm::vec3& c : obj.colors) top = std::max({top, c.r, c.g, c.b});
  const float scale = top > 1.0f ? 1.0f / 255.0f : 1.0f;
  std::vector<glm::vec4> out;
  out.reserve(obj.colors.size());
  for (const glm::vec3& c : obj.colors) {
    const glm::vec3 display = glm::clamp(c * scale, 0.0f, 1.0f);
    out.emplace_back(eng::srgbToLinear(display.r), eng::srgbToLinear(display.g), eng::srgbToLinear(display.b), 1.0f);
  }
  return out;
}

Result<std::vector<PrimitiveBuild>> buildNeutral(const ObjPolygonMesh& obj, std::vector<std::string>& warnings) {
  const std::vector<glm::vec4> colours = linearColours(obj);
  std::vector<PrimitiveBuild> builds;
  std::vector<std::unordered_map<CornerKey, uint32_t, CornerKeyHash>> vertexOf;
  std::unordered_map<int, size_t> primOfMaterial;
  for (size_t f = 0; f < obj.faceCount(); ++f) {
    const int material = obj.faceMaterial[f];
    auto [it, added] = primOfMaterial.try_emplace(material, builds.size());
    if (added) {
      builds.emplace_back();
      builds.back().prim.material = material;
      vertexOf.emplace_back();
      vertexOf.back().reserve(obj.corners.size() / std::max<size_t>(1, primOfMaterial.size()));
    }
    PrimitiveBuild& b = builds[it->second];
    auto& map = vertexOf[it->second];
    const size_t n = obj.faceSize(f);
    uint32_t faceVertex[3] = {0, 0, 0};
    for (size_t k = 0; k < n; ++k) {
      const ObjCorner& c = obj.corner(f, k);
      auto [vit, isNew] = map.try_emplace(CornerKey{c.v, c.vt, c.vn}, static_cast<uint32_t>(b.prim.positions.size()));
      if (isNew) {
        b.prim.positions.push_back(obj.positions[c.v]);
        if (!colours.empty()) b.prim.colors.push_back(colours[size_t(c.v)]);
        // OBJ's V axis points up, glTF's down.
        b.prim.texcoords.push_back(c.vt >= 0 ? glm::vec2(obj.texcoords[c.vt].x, 1.0f - obj.texcoords[c.vt].y) : glm::vec2(0.0f));
        b.anyTexcoords |= c.vt >= 0;
        glm::vec3 normal(0.0f);
        bool usable = c.vn >= 0;
        if (usable) {
          normal = obj.normals[c.vn];
          normalizeOr(normal, usable);
        }
        b.explicitNormals &= usable;
        b.prim.normals.push_back(normal);
        b.firstCorner.push_back(obj.faceStart[f] + static_cast<uint32_t>(k));
      }
      // Fan triangulation (0, k-1, k); faces with fewer than 3 corners add nothing.
      if (k == 0) faceVertex[0] = vit->second;
      else if (k == 1) faceVertex[1] = vit->second;
      else {
        b.prim.indices.insert(b.prim.indices.end(), {faceVertex[0], faceVertex[1], vit->second});
        faceVertex[1] = vit->second;
      }
    }
  }
  for (PrimitiveBuild& b : builds) {
    if (!b.anyTexcoords) b.prim.texcoords.clear();
    b.generatedNeutralNormals = computeSmoothNormals(b.prim.positions, b.prim.indices);
    if (!b.explicitNormals) {
      if (!obj.normals.empty())
        warnings.push_back("some faces have no (or zero) normals; smooth normals generated for their primitive");
      b.prim.normals = b.generatedNeutralNormals;
    }
  }
  return builds;
}

// Target deltas for one primitive through the corner map.
MorphTarget targetDeltas(const PrimitiveBuild& b, const ObjPolygonMesh& target, const ObjCornerMap& map,
                         const ObjPolygonMesh& neutral, size_t& moved) {
  const size_t n = b.prim.positions.size();
  MorphTarget t;
  t.positions.resize(n);
  t.normals.resize(n);
  std::vector<glm::vec3> movedPositions(n);
  std::vector<int32_t> targetNormal(n, -1);
  bool allExplicit = b.explicitNormals;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t nc = b.firstCorner[i];
    const int32_t tc = map.targetCorner[nc];
    int32_t tv = -1;
    if (tc >= 0) {
      tv = target.corners[tc].v;
      targetNormal[i] = target.corners[tc].vn;
    } else {
      tv = map.targetVertex[neutral.corners[nc].v];
    }
    movedPositions[i] = tv >= 0 ? target.positions[tv] : b.prim.positions[i];
    t.positions[i] = movedPositions[i] - b.prim.positions[i];
    if (t.positions[i] != glm::vec3(0.0f)) ++moved;
    allExplicit &= targetNormal[i] >= 0;
  }
  if (allExplicit) {
    for (size_t i = 0; i < n; ++i) {
      glm::vec3 normal = target.normals[targetNormal[i]];
      bool usable = true;
      normalizeOr(normal, usable);
      t.normals[i] = usable ? normal - b.prim.normals[i] : glm::vec3(0.0f);
    }
  } else {
    // Without normals on both sides, morph by the change of the smooth
    // normal, so unmoved regions get exactly zero deltas.
    const std::vector<glm::vec3> movedNormals = computeSmoothNormals(movedPositions, b.prim.indices);
    for (size_t i = 0; i < n; ++i) t.normals[i] = movedNormals[i] - b.generatedNeutralNormals[i];
  }
  return t;
}

// Target names become morph target names: each must be non-empty and used once.
Result<void> checkTargetNames(std::span<const ObjTargetFile> targets) {
  std::set<std::string> names;
  for (const ObjTargetFile& t : targets) {
    if (t.name.empty()) return makeError(ErrorKind::Malformed, t.path.string() + ": target name is empty");
    if (!names.insert(t.name).second) return makeError(ErrorKind::Malformed, t.path.string() + ": target name '" + t.name + "' is used twice");
  }
  return {};
}

// Reads one target OBJ, matches its corners to the neutral's (by position or
// strictly by topology) and adds its deltas to every primitive.
Result<ObjTargetReport> addTargetFile(const ObjTargetFile& file, const ObjPolygonMesh& neutral,
                                      const std::filesystem::path& neutralPath, const ObjKeyframeOptions& options,
                                      float tolerance, std::vector<PrimitiveBuild>& builds, std::vector<std::string>& warnings) {
  auto target = readObjPolygonMesh(file.path, ObjReadOptions{.materials = false});
  if (!target) return target.error();
  for (const std::string& w : target->warnings) warnings.push_back(file.path.filename().string() + ": " + w);
  ObjCornerMap map;
  if (options.matchByPosition) {
    map = matchObjByPosition(neutral, *target, tolerance);
  } else {
    auto strict = matchObjByTopology(neutral, *target, neutralPath.string(), file.path.string());
    if (!strict) return strict.error();
    map = std::move(*strict);
  }
  ObjTargetReport report{file.name, 0, map.unmatchedVertices};
  for (PrimitiveBuild& b : builds) b.prim.targets.push_back(targetDeltas(b, *target, map, neutral, report.movedVertices));
  return report;
}

// One glTF material per OBJ material; an unreadable texture is a warning.
Material materialFromObj(const ObjMaterial& src, Model& model) {
  Material mat;
  mat.name = src.name;
  mat.baseColorFactor = src.diffuse;
  mat.roughness = 0.6f;
  mat.metallic = 0.0f;
  if (!src.diffuseTexture.empty()) {
    auto image = readImage(src.diffuseTexture);
    if (image) {
      image->name = src.diffuseTexture.filename().string();
      mat.baseColorImage = static_cast<int>(model.images.size());
      model.images.push_back(std::move(*image));
    } else {
      model.warnings.push_back("material '" + src.name + "': texture skipped: " + image.error().message);
    }
  }
  return mat;
}

// Materials: only those faces use, in the order the primitives met them;
// renumbers each primitive's material from the OBJ's list to the model's.
void addUsedMaterials(Mesh& mesh, const std::vector<ObjMaterial>& objMaterials, Model& model) {
  std::unordered_map<int, int> materialRemap;
  for (Primitive& prim : mesh.primitives) {
    if (prim.material < 0) continue;
    auto [it, added] = materialRemap.try_emplace(prim.material, static_cast<int>(model.materials.size()));
    if (added) model.materials.push_back(materialFromObj(objMaterials[prim.material], model));
    prim.material = it->second;
  }
}

std::string lowerExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The model of `neutral` (read from `neutralPath`, which names the mesh and its messages) with `targets` on it.
Result<ObjKeyframeImport> importKeyframesOnto(const ObjPolygonMesh& neutral, const std::filesystem::path& neutralPath,
                                              std::span<const ObjTargetFile> targets, const ObjKeyframeOptions& options);

}  // namespace

Result<ObjKeyframeImport> importObjKeyframes(const std::filesystem::path& neutralPath, std::span<const ObjTargetFile> targets,
                                             const ObjKeyframeOptions& options, std::span<const uint8_t> neutralBytes) {
  if (auto named = checkTargetNames(targets); !named) return named.error();
  if (options.matchByPosition && !(options.relativeTolerance > 0.0f && options.relativeTolerance <= kMaxRelativeTolerance))
    return makeError(ErrorKind::InvalidArgument, "tolerance " + facial::formatNumber(options.relativeTolerance) +
                                                     " is outside (0, " + facial::formatNumber(kMaxRelativeTolerance) +
                                                     "] of the model's size: distinct vertices would be matched");
  auto neutral = readObjPolygonMesh(neutralPath, {}, neutralBytes);
  if (!neutral) return neutral.error();
  return importKeyframesOnto(*neutral, neutralPath, targets, options);
}

Result<Model> modelFromPolygonMesh(const ObjPolygonMesh& mesh, const std::filesystem::path& path) {
  auto imported = importKeyframesOnto(mesh, path, {}, {});
  if (!imported) return imported.error();
  return std::move(imported->model);
}

namespace {

Result<ObjKeyframeImport> importKeyframesOnto(const ObjPolygonMesh& neutralMesh, const std::filesystem::path& neutralPath,
                                              std::span<const ObjTargetFile> targets, const ObjKeyframeOptions& options) {
  const ObjPolygonMesh* neutral = &neutralMesh;
  ObjKeyframeImport result;
  Model& model = result.model;
  model.sourcePath = neutralPath.string();
  for (const std::string& w : neutral->warnings) model.warnings.push_back(neutralPath.filename().string() + ": " + w);
  auto builds = buildNeutral(*neutral, model.warnings);
  if (!builds) return builds.error();

  Aabb box;
  for (const glm::vec3& p : neutral->positions) box.extend(p);
  const float tolerance = std::max(box.diagonal() * options.relativeTolerance, 1e-12f);
  for (const ObjTargetFile& file : targets) {
    auto report = addTargetFile(file, *neutral, neutralPath, options, tolerance, *builds, model.warnings);
    if (!report) return report.error();
    result.targets.push_back(std::move(*report));
  }

  Mesh mesh;
  mesh.name = neutralPath.stem().string();
  for (const ObjTargetFile& t : targets) mesh.targetNames.push_back(t.name);
  mesh.defaultWeights.assign(targets.size(), 0.0f);
  for (PrimitiveBuild& b : *builds) mesh.primitives.push_back(std::move(b.prim));
  addUsedMaterials(mesh, neutral->materials, model);
  model.meshes.push_back(std::move(mesh));
  Node node;
  node.name = model.meshes[0].name;
  node.mesh = 0;
  model.nodes.push_back(std::move(node));
  model.roots = {0};
  // Finite OBJ coordinates can still give non-finite morph deltas (a target
  // vertex 3e38 away from its neutral one): refused here, by file, rather
  // than handed on to the renderer.
  if (auto consistent = checkModel(model); !consistent)
    return consistent.error().prefixed(neutralPath.string() + ": ");
  return result;
}

}  // namespace

Result<ObjKeyframeFolder> findObjKeyframeFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return makeError(ErrorKind::Io, dir.string() + ": not a folder");
  ObjKeyframeFolder folder;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (!entry.is_regular_file(ec) || lowerExtension(entry.path()) != ".obj") continue;
    if (entry.path().stem() == "neutral") folder.neutral = entry.path();
    else folder.targets.push_back({entry.path().stem().string(), entry.path()});
  }
  if (ec) return makeError(ErrorKind::Io, dir.string() + ": cannot list (" + ec.message() + ")");
  if (folder.neutral.empty()) return makeError(ErrorKind::NotFound, dir.string() + ": no neutral.obj in the folder");
  std::sort(folder.targets.begin(), folder.targets.end(),
            [](const ObjTargetFile& a, const ObjTargetFile& b) { return a.name < b.name; });
  return folder;
}

}  // namespace importers
