#include "importers/ply_mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/confined_path.h"
#include "engine/core/load_budget.h"
#include "engine/core/text_lines.h"

namespace importers {
namespace {

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

eng::Error plyError(const std::filesystem::path& path, const std::string& what) {
  return eng::Error{eng::ErrorKind::Malformed, path.string() + ": " + what};
}

// Bytes of one value of a PLY scalar type; 0 for an unknown type.
size_t scalarBytes(std::string_view type) {
  for (std::string_view one : {"char", "uchar", "int8", "uint8"}) if (type == one) return 1;
  for (std::string_view two : {"short", "ushort", "int16", "uint16"}) if (type == two) return 2;
  for (std::string_view four : {"int", "uint", "float", "int32", "uint32", "float32"}) if (type == four) return 4;
  for (std::string_view eight : {"double", "float64"}) if (type == eight) return 8;
  return 0;
}

// Every word after an ASCII header is a finite number: Assimp's reader takes
// "nan" or "1,5" for something else and reads on, misplacing the rest.
eng::Result<void> checkAsciiNumbers(std::string_view text, size_t at, size_t line, const std::filesystem::path& path) {
  while (at < text.size()) {
    const char c = text[at];
    if (c == '\n') {
      ++line, ++at;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      ++at;
      continue;
    }
    const size_t end = std::min(text.find_first_of(" \t\r\n", at), text.size());
    const std::string_view word = text.substr(at, end - at);
    double value = 0.0;
    const char* first = word.data() + (word.starts_with('+') ? 1 : 0);
    const auto [stop, ec] = std::from_chars(first, word.data() + word.size(), value);
    if (ec != std::errc() || stop != word.data() + word.size() || !std::isfinite(value))
      return plyError(path, "line " + std::to_string(line) + ": '" + std::string(word.substr(0, 32)) + "' is not a finite number");
    at = end;
  }
  return {};
}

// The header read before Assimp sees the file: each element's count must fit
// in the bytes after the header (a binary record is at least its scalars and
// list counts long, an ASCII one two characters per property), so a header
// claiming billions of vertices is refused by its sizes instead of making the
// reader allocate for them; what the vertices and corners will take once read
// is charged to a load budget.
eng::Result<void> checkHeader(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  constexpr size_t kMostHeaderBytes = size_t{1} << 16;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min(bytes.size(), kMostHeaderBytes));
  const size_t end = text.find("end_header");
  if (end == std::string_view::npos)
    return plyError(path, "no 'end_header' in the first " + std::to_string(text.size()) + " bytes");
  const size_t newline = text.find('\n', end);
  const size_t body = newline == std::string_view::npos ? bytes.size() : newline + 1;
  eng::TextLines lines(text.substr(0, end));
  std::string_view line;
  bool ascii = false, knownFormat = false;
  struct Element {
    std::string name;
    size_t count = 0;
    size_t leastBytes = 0;
  };
  std::vector<Element> elements;
  while (lines.nextNonBlank(line)) {
    std::vector<std::string_view> words;
    for (size_t at = 0; at < line.size();) {
      const size_t next = std::min(line.find_first_of(" \t", at), line.size());
      if (next > at) words.push_back(line.substr(at, next - at));
      at = next + 1;
    }
    if (words.empty()) continue;
    if (words[0] == "format" && words.size() >= 2) {
      knownFormat = words[1] == "ascii" || words[1] == "binary_little_endian" || words[1] == "binary_big_endian";
      ascii = words[1] == "ascii";
      if (!knownFormat) return plyError(path, "format '" + std::string(words[1]) + "' is none of ascii, binary_little_endian, binary_big_endian");
    } else if (words[0] == "element" && words.size() >= 3) {
      Element e;
      e.name = words[1];
      const std::string count(words[2]);
      char* stop = nullptr;
      const unsigned long long n = std::strtoull(count.c_str(), &stop, 10);
      if (count.empty() || *stop != '\0' || count[0] == '-')
        return plyError(path, "element '" + e.name + "' has the count '" + count + "'");
      e.count = size_t(std::min<unsigned long long>(n, SIZE_MAX));
      elements.push_back(std::move(e));
    } else if (words[0] == "property" && !elements.empty()) {
      const bool list = words.size() >= 2 && words[1] == "list";
      const size_t bytesOfType = scalarBytes(list ? (words.size() >= 3 ? words[2] : "") : (words.size() >= 2 ? words[1] : ""));
      if (bytesOfType == 0) return plyError(path, "property '" + std::string(line) + "' has an unknown type");
      elements.back().leastBytes += ascii ? 2 : bytesOfType;
    }
  }
  if (!knownFormat) return plyError(path, "no 'format' line in the header");
  const size_t after = bytes.size() - std::min(body, bytes.size());
  size_t least = 0;
  eng::LoadBudget budget;
  for (const Element& e : elements) {
    const size_t each = std::max<size_t>(e.leastBytes, 1);
    if (e.count > after / each || least + e.count * each > after)
      return plyError(path, "element '" + e.name + "' claims " + std::to_string(e.count) + " records of at least " +
                                std::to_string(each) + " bytes; the file has " + std::to_string(after) + " after its header");
    least += e.count * each;
    // Read, a vertex keeps about 64 bytes of attributes and a face its corners, each a vertex of its own until joined.
    if (auto charged = budget.charge(e.count, e.name == "face" ? 3 * 64 : 64, "element '" + e.name + "'"); !charged)
      return charged.error().prefixed(path.string() + ": ");
  }
  if (std::none_of(elements.begin(), elements.end(), [](const Element& e) { return e.name == "face" && e.count > 0; }))
    return plyError(path, "no faces (a point cloud: a face needs a surface)");
  if (ascii) ENG_TRY(checkAsciiNumbers(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), body,
                                       lines.number() + 2, path));
  return {};
}

void copyMaterials(const aiScene& scene, const std::filesystem::path& dir, ObjPolygonMesh& out) {
  for (unsigned m = 0; m < scene.mNumMaterials; ++m) {
    const aiMaterial& material = *scene.mMaterials[m];
    ObjMaterial copied;
    copied.name = material.GetName().C_Str();
    aiColor4D diffuse;
    if (material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS &&
        std::isfinite(diffuse.r + diffuse.g + diffuse.b + diffuse.a))
      copied.diffuse = glm::clamp(glm::vec4(diffuse.r, diffuse.g, diffuse.b, diffuse.a), 0.0f, 1.0f);
    aiString texture;
    if (material.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS && texture.length > 0) {
      auto resolved = eng::resolveInsideFolder(dir, texture.C_Str());
      if (resolved) copied.diffuseTexture = *resolved;
      else out.warnings.push_back("texture '" + std::string(texture.C_Str()) + "' is outside the PLY's folder; ignored");
    }
    out.materials.push_back(std::move(copied));
  }
}

// Appends one Assimp mesh placed by `placed` (its node's world transform).
eng::Result<void> appendMesh(const aiMesh& mesh, const aiMatrix4x4& placed, bool withUv, bool withNormals, bool withColours,
                             const std::filesystem::path& path, ObjPolygonMesh& out) {
  const size_t base = out.positions.size();
  aiMatrix3x3 turn(placed);
  turn.Inverse().Transpose();  // normals: the inverse transpose
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D p = placed * mesh.mVertices[v];
    if (!finite(p)) return plyError(path, "vertex " + std::to_string(base + v) + " is not finite");
    out.positions.emplace_back(p.x, p.y, p.z);
    if (withNormals) {
      const aiVector3D n = turn * mesh.mNormals[v];
      out.normals.emplace_back(finite(n) ? glm::vec3(n.x, n.y, n.z) : glm::vec3(0.0f));
    }
    if (withUv) {
      const aiVector3D& t = mesh.mTextureCoords[0][v];
      out.texcoords.emplace_back(std::isfinite(t.x) ? t.x : 0.0f, std::isfinite(t.y) ? t.y : 0.0f);
    }
    if (withColours) {
      const aiColor4D& c = mesh.mColors[0][v];
      out.colors.emplace_back(std::isfinite(c.r) ? c.r : 1.0f, std::isfinite(c.g) ? c.g : 1.0f, std::isfinite(c.b) ? c.b : 1.0f);
    }
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices < 3) continue;  // points and edges: nothing to draw
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices)
        return plyError(path, "face " + std::to_string(f) + " names vertex " + std::to_string(face.mIndices[k]) + " of " +
                                  std::to_string(mesh.mNumVertices));
      const int v = int(base + face.mIndices[k]);
      out.corners.push_back({v, withUv ? v : -1, withNormals ? v : -1});
    }
    out.faceStart.push_back(uint32_t(out.corners.size()));
    out.faceMaterial.push_back(mesh.mMaterialIndex < out.materials.size() ? int(mesh.mMaterialIndex) : -1);
  }
  return {};
}

}  // namespace

bool looksLikePly(std::span<const uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 5));
  return text == "ply\n" || text == "ply\r\n" || text.starts_with("ply\n") || text.starts_with("ply\r");
}

eng::Result<ObjPolygonMesh> readPlyPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  ENG_TRY(checkHeader(bytes, path));
  Assimp::Importer importer;
  // No post-processing but the check of what it built: the file's vertices
  // stay as they are (shared by its faces), non-finite ones included, so
  // appendMesh can name them.
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(),
                                                     aiProcess_ValidateDataStructure, "ply");
  if (!scene) return plyError(path, std::string("not a PLY this program reads (") + importer.GetErrorString() + ")");
  if (!scene->mRootNode || scene->mNumMeshes == 0) return plyError(path, "no faces");

  ObjPolygonMesh out;
  out.faceStart.push_back(0);
  copyMaterials(*scene, path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path(), out);
  // The attributes the whole file has (a vertex without one would leave a hole in the array).
  bool withUv = true, withNormals = true, withColours = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    withUv &= scene->mMeshes[m]->HasTextureCoords(0);
    withNormals &= scene->mMeshes[m]->HasNormals();
    withColours &= scene->mMeshes[m]->HasVertexColors(0);
  }
  // Depth-first over the nodes, each mesh placed by its node's world transform.
  struct Visit {
    const aiNode* node;
    aiMatrix4x4 world;
  };
  std::vector<Visit> stack{{scene->mRootNode, scene->mRootNode->mTransformation}};
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    for (unsigned i = 0; i < visit.node->mNumMeshes; ++i) {
      const unsigned m = visit.node->mMeshes[i];
      if (m >= scene->mNumMeshes) return plyError(path, "a node names mesh " + std::to_string(m));
      ENG_TRY(appendMesh(*scene->mMeshes[m], visit.world, withUv, withNormals, withColours, path, out));
    }
    for (unsigned c = 0; c < visit.node->mNumChildren; ++c)
      stack.push_back({visit.node->mChildren[c], visit.world * visit.node->mChildren[c]->mTransformation});
  }
  if (out.faceCount() == 0) return plyError(path, "no faces (a point cloud: a face needs a surface)");
  return out;
}

}  // namespace importers
