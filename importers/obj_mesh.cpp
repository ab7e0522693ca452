#include "importers/obj_mesh.h"

#include <cmath>
#include <sstream>

#include <tiny_obj_loader.h>

#include "engine/core/confined_path.h"
#include "engine/scene/file_bytes.h"

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

// Resolves a file named inside an OBJ/MTL to a path in `dir`, or empty when it would leave it.
std::filesystem::path confined(const std::filesystem::path& dir, const std::string& name) {
  auto path = eng::resolveInsideFolder(dir, name);
  return path ? *path : std::filesystem::path();
}

// tinyobjloader's mtllib hook, reading only .mtl files beside the OBJ.
class ConfinedMaterialReader : public tinyobj::MaterialReader {
 public:
  ConfinedMaterialReader(std::filesystem::path dir, bool enabled) : dir_(std::move(dir)), enabled_(enabled) {}

  bool operator()(const std::string& matId, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* matMap, std::string* warn, std::string* err) override {
    if (!enabled_) return true;
    const std::filesystem::path path = confined(dir_, matId);
    if (path.empty()) {
      if (warn) *warn += "material library '" + matId + "' is outside the OBJ's folder; refused\n";
      return true;
    }
    auto bytes = readFileBytes(path, size_t{64} << 20);
    if (!bytes) {
      if (warn) *warn += "material library '" + matId + "' not read: " + bytes.error().message + "\n";
      return true;
    }
    std::istringstream in(std::string(bytes->begin(), bytes->end()));
    tinyobj::LoadMtl(matMap, materials, &in, warn, err);
    return true;
  }

 private:
  std::filesystem::path dir_;
  bool enabled_;
};

template <class Vec>
Result<void> copyFinite(const std::vector<tinyobj::real_t>& src, std::vector<Vec>& out, const char* what) {
  constexpr int n = Vec::length();
  out.resize(src.size() / n);
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < n; ++c) {
      const float v = src[i * n + c];
      if (!std::isfinite(v))
        return makeError(ErrorKind::Malformed, std::string(what) + " " + std::to_string(i + 1) + " is " + (std::isnan(v) ? "NaN" : "infinite"));
      out[i][c] = v;
    }
  return {};
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

// Errors: a corner naming a vertex, texcoord or normal the file does not have
// (1-based, as in the file). A missing texcoord or normal is -1 and allowed.
Result<void> checkCorner(const tinyobj::index_t& idx, const ObjPolygonMesh& mesh, const std::string& file) {
  const int nv = static_cast<int>(mesh.positions.size());
  const int nt = static_cast<int>(mesh.texcoords.size());
  const int nn = static_cast<int>(mesh.normals.size());
  const size_t face = mesh.faceCount() + 1;
  if (idx.vertex_index < 0 || idx.vertex_index >= nv)
    return makeError(ErrorKind::Malformed, file + ": face " + std::to_string(face) + " uses vertex " + std::to_string(idx.vertex_index + 1) +
                     ", the file has " + std::to_string(nv));
  if (idx.texcoord_index >= nt || idx.texcoord_index < -1)
    return makeError(ErrorKind::Malformed, file + ": face " + std::to_string(face) + " uses texcoord " +
                     std::to_string(idx.texcoord_index + 1) + ", the file has " + std::to_string(nt));
  if (idx.normal_index >= nn || idx.normal_index < -1)
    return makeError(ErrorKind::Malformed, file + ": face " + std::to_string(face) + " uses normal " + std::to_string(idx.normal_index + 1) +
                     ", the file has " + std::to_string(nn));
  return {};
}

// The shapes' polygons, all into one flat corner list, with each face's
// material (-1 where it names none the file defines).
Result<void> copyFaces(const std::vector<tinyobj::shape_t>& shapes, size_t materialCount, const std::string& file,
                       ObjPolygonMesh& mesh) {
  mesh.faceStart.push_back(0);
  for (const tinyobj::shape_t& shape : shapes) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t count = shape.mesh.num_face_vertices[f];
      if (offset + count > shape.mesh.indices.size())
        return makeError(ErrorKind::Malformed, file + ": face " + std::to_string(mesh.faceCount() + 1) + " has missing corners");
      for (size_t k = 0; k < count; ++k) {
        const tinyobj::index_t& idx = shape.mesh.indices[offset + k];
        if (auto r = checkCorner(idx, mesh, file); !r) return r.error();
        mesh.corners.push_back({idx.vertex_index, idx.texcoord_index, idx.normal_index});
      }
      offset += count;
      mesh.faceStart.push_back(static_cast<uint32_t>(mesh.corners.size()));
      const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      mesh.faceMaterial.push_back(material >= 0 && material < static_cast<int>(materialCount) ? material : -1);
    }
  }
  return {};
}

// The MTL materials, with a non-finite colour replaced by white and a texture
// outside the OBJ's folder dropped (each with a warning).
void copyMaterials(const std::vector<tinyobj::material_t>& materials, const std::filesystem::path& dir, ObjPolygonMesh& mesh) {
  for (const tinyobj::material_t& m : materials) {
    ObjMaterial out;
    out.name = m.name;
    out.diffuse = glm::vec4(m.diffuse[0], m.diffuse[1], m.diffuse[2], m.dissolve);
    if (!std::isfinite(out.diffuse.r + out.diffuse.g + out.diffuse.b + out.diffuse.a)) {
      mesh.warnings.push_back("material '" + m.name + "' has non-finite Kd/d; white used");
      out.diffuse = glm::vec4(1.0f);
    }
    if (!m.diffuse_texname.empty()) {
      out.diffuseTexture = confined(dir, m.diffuse_texname);
      if (out.diffuseTexture.empty())
        mesh.warnings.push_back("material '" + m.name + "': texture '" + m.diffuse_texname +
                                "' is outside the OBJ's folder; ignored");
    }
    mesh.materials.push_back(std::move(out));
  }
}

}  // namespace

Result<ObjPolygonMesh> readObjPolygonMesh(const std::filesystem::path& path, const ObjReadOptions& options,
                                          std::span<const uint8_t> given) {
  const std::string file = path.string();
  std::vector<uint8_t> read;
  if (given.empty()) {
    auto bytes = readFileBytes(path, options.maxFileBytes);
    if (!bytes) return bytes.error();
    read = std::move(*bytes);
    given = read;
  }
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::absolute(path, ec).parent_path().lexically_normal();

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  ConfinedMaterialReader mtl(dir, options.materials);
  std::istringstream in(std::string(given.begin(), given.end()));
  read.clear();
  read.shrink_to_fit();
  // triangulate = false: topology is compared on the file's own polygons.
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl, false, false);
  if (!ok) {
    std::string message = err.empty() ? "not a readable OBJ" : err;
    while (!message.empty() && message.back() == '\n') message.pop_back();
    for (char& c : message)
      if (c == '\n') c = ' ';
    return makeError(ErrorKind::Malformed, file + ": " + message);
  }

  ObjPolygonMesh mesh;
  if (auto r = copyFinite(attrib.vertices, mesh.positions, "vertex"); !r) return r.error().prefixed(file + ": ");
  if (auto r = copyFinite(attrib.texcoords, mesh.texcoords, "texcoord"); !r)
    return r.error().prefixed(file + ": ");
  if (auto r = copyFinite(attrib.normals, mesh.normals, "normal"); !r) return r.error().prefixed(file + ": ");
  if (mesh.positions.empty()) return makeError(ErrorKind::Malformed, file + ": no vertices ('v' lines)");
  if (attrib.colors.size() == attrib.vertices.size())
    if (auto r = copyFinite(attrib.colors, mesh.colors, "vertex colour"); !r) return r.error().prefixed(file + ": ");

  if (auto r = copyFaces(shapes, materials.size(), file, mesh); !r) return r.error();
  if (mesh.faceCount() == 0) return makeError(ErrorKind::Malformed, file + ": no faces ('f' lines)");

  copyMaterials(materials, dir, mesh);
  for (std::string& line : lines(warn)) mesh.warnings.push_back(std::move(line));
  return mesh;
}

}  // namespace importers
