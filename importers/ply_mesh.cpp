#include "importers/ply_mesh.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/core/confined_path.h"
#include "engine/core/text_lines.h"

// Read by hand: Assimp 5.2.5's PLY reader (Debian's) crashed in its first
// minute under the fuzzer (a property line run into end_header). This one
// checks every count against the bytes left before it reads.
namespace importers {
namespace {

enum class Scalar : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Scalar> scalarNamed(std::string_view type) {
  if (type == "char" || type == "int8") return Scalar::Int8;
  if (type == "uchar" || type == "uint8") return Scalar::UInt8;
  if (type == "short" || type == "int16") return Scalar::Int16;
  if (type == "ushort" || type == "uint16") return Scalar::UInt16;
  if (type == "int" || type == "int32") return Scalar::Int32;
  if (type == "uint" || type == "uint32") return Scalar::UInt32;
  if (type == "float" || type == "float32") return Scalar::Float32;
  if (type == "double" || type == "float64") return Scalar::Float64;
  return std::nullopt;
}

size_t bytesOf(Scalar s) {
  switch (s) {
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: return 2;
    case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 1;
}

// The largest value of an unsigned integer type (colours in bytes or shorts
// become 0-1); 1 for the others.
double colourScale(Scalar s) {
  return s == Scalar::UInt8 ? 255.0 : s == Scalar::UInt16 ? 65535.0 : 1.0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;
  bool list = false;
  Scalar countType = Scalar::UInt8;
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding : uint8_t { Ascii, LittleEndian, BigEndian };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::string textureFile;  // MeshLab's "comment TextureFile NAME"
  size_t bodyStart = 0;     // the byte after the end_header line
  size_t bodyLine = 0;      // its line number (ASCII messages)
};

std::vector<std::string_view> wordsOf(std::string_view line) {
  std::vector<std::string_view> words;
  for (size_t at = 0; at < line.size();) {
    const size_t next = std::min(line.find_first_of(" \t", at), line.size());
    if (next > at) words.push_back(line.substr(at, next - at));
    at = next + 1;
  }
  return words;
}

eng::Error plyError(const std::filesystem::path& path, const std::string& what) {
  return eng::makeError(eng::ErrorKind::Malformed, path.string() + ": " + what);
}

eng::Result<Header> readHeader(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  constexpr size_t kMostHeaderBytes = size_t{1} << 16;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min(bytes.size(), kMostHeaderBytes));
  Header header;
  bool format = false, ended = false;
  size_t at = 0, number = 0;
  while (at < text.size() && !ended) {
    const size_t newline = text.find('\n', at);
    if (newline == std::string_view::npos) break;  // the header's last line ends before the body
    const std::string_view line = eng::trimmed(text.substr(at, newline - at));
    at = newline + 1;
    ++number;
    const std::vector<std::string_view> w = wordsOf(line);
    const std::string where = "header line " + std::to_string(number) + ": ";
    if (number == 1) {
      if (line != "ply") return plyError(path, "not a PLY file (its first line is not 'ply')");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") {
      if (w.size() >= 3 && w[0] == "comment" && w[1] == "TextureFile")
        header.textureFile = std::string(eng::trimmed(line.substr(line.find("TextureFile") + 11)));
      continue;
    }
    if (w[0] == "format") {
      if (w.size() != 3 || w[2] != "1.0") return plyError(path, where + "'" + eng::shownText(line) + "' is not 'format <encoding> 1.0'");
      if (w[1] == "ascii") header.encoding = Encoding::Ascii;
      else if (w[1] == "binary_little_endian") header.encoding = Encoding::LittleEndian;
      else if (w[1] == "binary_big_endian") header.encoding = Encoding::BigEndian;
      else return plyError(path, where + "format '" + eng::shownText(w[1]) + "' is none of ascii, binary_little_endian, binary_big_endian");
      format = true;
    } else if (w[0] == "element") {
      uint64_t count = 0;
      const auto [end, ec] = w.size() == 3 ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), count)
                                           : std::from_chars_result{nullptr, std::errc::invalid_argument};
      if (ec != std::errc() || end != w[2].data() + w[2].size())
        return plyError(path, where + "'" + eng::shownText(line) + "' is not 'element <name> <count>'");
      header.elements.push_back({std::string(w[1]), size_t(count), {}});
    } else if (w[0] == "property") {
      if (header.elements.empty()) return plyError(path, where + "a property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        const auto count = scalarNamed(w[2]), item = scalarNamed(w[3]);
        if (!count || !item || *count == Scalar::Float32 || *count == Scalar::Float64)
          return plyError(path, where + "'" + eng::shownText(line) + "' has an unknown or non-integer count type");
        p = {std::string(w[4]), *item, true, *count};
      } else if (w.size() == 3) {
        const auto type = scalarNamed(w[1]);
        if (!type) return plyError(path, where + "'" + eng::shownText(line) + "' has an unknown type");
        p = {std::string(w[2]), *type, false, Scalar::UInt8};
      } else {
        return plyError(path, where + "'" + eng::shownText(line) + "' is not 'property <type> <name>' or a list");
      }
      header.elements.back().properties.push_back(std::move(p));
    } else if (line == "end_header") {
      ended = true;
    } else {
      return plyError(path, where + "'" + eng::shownText(line) + "' is not a PLY header line");
    }
  }
  if (!ended) return plyError(path, "no 'end_header' line in the first " + std::to_string(text.size()) + " bytes");
  if (!format) return plyError(path, "no 'format' line in the header");
  header.bodyStart = at;
  header.bodyLine = number + 1;
  return header;
}

// The body, value by value: ASCII words or binary scalars, every read checked
// against the bytes left.
class BodyReader {
 public:
  BodyReader(std::span<const uint8_t> bytes, const Header& header, const std::filesystem::path& path)
      : bytes_(bytes), at_(header.bodyStart), line_(header.bodyLine), encoding_(header.encoding), path_(path) {}

  eng::Result<double> next(Scalar type) {
    if (encoding_ == Encoding::Ascii) return nextWord();
    const size_t n = bytesOf(type);
    if (bytes_.size() - at_ < n)
      return plyError(path_, "the body ends at byte " + std::to_string(bytes_.size()) + ", short of the records the header declares");
    uint8_t raw[8];
    std::memcpy(raw, bytes_.data() + at_, n);
    at_ += n;
    if ((encoding_ == Encoding::BigEndian) != (std::endian::native == std::endian::big)) std::reverse(raw, raw + n);
    switch (type) {
      case Scalar::Int8: return double(int8_t(raw[0]));
      case Scalar::UInt8: return double(raw[0]);
      case Scalar::Int16: { int16_t v; std::memcpy(&v, raw, 2); return double(v); }
      case Scalar::UInt16: { uint16_t v; std::memcpy(&v, raw, 2); return double(v); }
      case Scalar::Int32: { int32_t v; std::memcpy(&v, raw, 4); return double(v); }
      case Scalar::UInt32: { uint32_t v; std::memcpy(&v, raw, 4); return double(v); }
      case Scalar::Float32: { float v; std::memcpy(&v, raw, 4); return double(v); }
      case Scalar::Float64: { double v; std::memcpy(&v, raw, 8); return v; }
    }
    return 0.0;
  }
  // A list's length: a whole number no larger than the values the bytes left can hold.
  eng::Result<size_t> listLength(Scalar type) {
    const double n = ENG_TRY_VALUE(next(type));
    if (!(n >= 0.0) || n != std::floor(n) || n > double(bytes_.size()) || !roomFor(size_t(n)))
      return plyError(path_, where() + ": a list of " + std::to_string(n) + " values");
    return size_t(n);
  }
  // At least `least` more values can follow (each at least one byte in binary, two characters in ASCII).
  bool roomFor(size_t least) const {
    const size_t left = bytes_.size() - at_;
    return encoding_ == Encoding::Ascii ? least <= left / 2 + 1 : least <= left;
  }
  std::string where() const {
    return encoding_ == Encoding::Ascii ? "line " + std::to_string(line_) : "byte " + std::to_string(at_);
  }

 private:
  eng::Result<double> nextWord() {
    while (at_ < bytes_.size() && (bytes_[at_] == ' ' || bytes_[at_] == '\t' || bytes_[at_] == '\r' || bytes_[at_] == '\n')) {
      if (bytes_[at_] == '\n') ++line_;
      ++at_;
    }
    if (at_ == bytes_.size())
      return plyError(path_, "the body ends at line " + std::to_string(line_) + ", short of the records the header declares");
    const char* first = reinterpret_cast<const char*>(bytes_.data() + at_);
    size_t end = at_;
    while (end < bytes_.size() && bytes_[end] != ' ' && bytes_[end] != '\t' && bytes_[end] != '\r' && bytes_[end] != '\n') ++end;
    const std::string_view word(first, end - at_);
    double value = 0.0;
    const char* start = word.data() + (word.starts_with('+') ? 1 : 0);
    const auto [stop, ec] = std::from_chars(start, word.data() + word.size(), value);
    if (ec != std::errc() || stop != word.data() + word.size() || !std::isfinite(value))
      return plyError(path_, "line " + std::to_string(line_) + ": '" + eng::shownText(word) + "' is not a finite number");
    at_ = end;
    return value;
  }

  std::span<const uint8_t> bytes_;
  size_t at_;
  size_t line_;
  Encoding encoding_;
  const std::filesystem::path& path_;
};

// A read value as a float: beyond float's range (a double of 1e300) it is
// infinite, which the checks below refuse or replace, not a conversion C++
// leaves undefined.
float narrow(double v) {
  if (std::abs(v) <= double(std::numeric_limits<float>::max())) return float(v);
  return std::isnan(v) ? std::numeric_limits<float>::quiet_NaN() : std::copysign(std::numeric_limits<float>::infinity(), float(v > 0 ? 1 : -1));
}

// Which vertex property feeds which attribute (-1: none).
struct VertexLayout {
  int position[3] = {-1, -1, -1};
  int normal[3] = {-1, -1, -1};
  int uv[2] = {-1, -1};
  int colour[3] = {-1, -1, -1};

  explicit VertexLayout(const Element& e) {
    for (size_t i = 0; i < e.properties.size(); ++i) {
      if (e.properties[i].list) continue;
      const std::string& n = e.properties[i].name;
      const int k = int(i);
      if (n == "x") position[0] = k;
      else if (n == "y") position[1] = k;
      else if (n == "z") position[2] = k;
      else if (n == "nx") normal[0] = k;
      else if (n == "ny") normal[1] = k;
      else if (n == "nz") normal[2] = k;
      else if (n == "s" || n == "u" || n == "texture_u" || n == "texture_s") uv[0] = k;
      else if (n == "t" || n == "v" || n == "texture_v" || n == "texture_t") uv[1] = k;
      else if (n == "red" || n == "r" || n == "diffuse_red") colour[0] = k;
      else if (n == "green" || n == "g" || n == "diffuse_green") colour[1] = k;
      else if (n == "blue" || n == "b" || n == "diffuse_blue") colour[2] = k;
    }
  }
  static bool all(const int* k, int n) { return std::all_of(k, k + n, [](int i) { return i >= 0; }); }
};

eng::Result<void> readVertices(BodyReader& body, const Element& e, ObjPolygonMesh& out, const std::filesystem::path& path) {
  const VertexLayout layout(e);
  if (!VertexLayout::all(layout.position, 3)) return plyError(path, "element 'vertex' has no x, y and z");
  const bool normals = VertexLayout::all(layout.normal, 3), uvs = VertexLayout::all(layout.uv, 2),
             colours = VertexLayout::all(layout.colour, 3);
  std::vector<float> values(e.properties.size());
  for (size_t v = 0; v < e.count; ++v) {
    for (size_t p = 0; p < e.properties.size(); ++p) {
      const Property& property = e.properties[p];
      if (!property.list) {
        values[p] = narrow(ENG_TRY_VALUE(body.next(property.type)));
        continue;
      }
      const size_t n = ENG_TRY_VALUE(body.listLength(property.countType));
      for (size_t i = 0; i < n; ++i) (void)ENG_TRY_VALUE(body.next(property.type));
    }
    const glm::vec3 p(values[size_t(layout.position[0])], values[size_t(layout.position[1])], values[size_t(layout.position[2])]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return plyError(path, "vertex " + std::to_string(v) + " is not finite");
    out.positions.emplace_back(p);
    if (normals)
      out.normals.emplace_back(values[size_t(layout.normal[0])], values[size_t(layout.normal[1])], values[size_t(layout.normal[2])]);
    if (uvs) out.texcoords.emplace_back(values[size_t(layout.uv[0])], values[size_t(layout.uv[1])]);
    if (colours) {
      glm::vec3 c;
      for (int k = 0; k < 3; ++k) {
        const Property& property = e.properties[size_t(layout.colour[k])];
        c[k] = values[size_t(layout.colour[k])] / float(colourScale(property.type));
      }
      out.colors.push_back(std::isfinite(c.r + c.g + c.b) ? c : glm::vec3(1.0f));
    }
  }
  for (glm::vec3& n : out.normals)
    if (!std::isfinite(n.x + n.y + n.z)) n = glm::vec3(0.0f);  // generated again for its face (buildNeutral)
  for (glm::vec2& t : out.texcoords)
    if (!std::isfinite(t.x + t.y)) t = glm::vec2(0.0f);
  return {};
}

// Faces: "vertex_indices" (or "vertex_index"), and MeshLab's per-corner
// "texcoord" list (u v per corner) where a texture's seams split the UVs.
eng::Result<void> readFaces(BodyReader& body, const Element& e, ObjPolygonMesh& out, int material,
                            const std::filesystem::path& path) {
  int indices = -1, wedges = -1;
  for (size_t i = 0; i < e.properties.size(); ++i) {
    if (!e.properties[i].list) continue;
    if (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index") indices = int(i);
    if (e.properties[i].name == "texcoord") wedges = int(i);
  }
  if (indices < 0) return plyError(path, "element 'face' has no vertex_indices list");
  const bool vertexUvs = !out.texcoords.empty() && wedges < 0;
  const bool vertexNormals = !out.normals.empty();
  std::vector<int> corners;
  std::vector<glm::vec2> wedgeUv;
  // Corners of one vertex with the same UV share it (one texcoord), so the
  // surface stays joined but along the texture's seams.
  struct WedgeKey {
    int vertex;
    uint32_t u, v;
    bool operator==(const WedgeKey&) const = default;
  };
  struct WedgeHash {
    size_t operator()(const WedgeKey& k) const {
      return std::hash<uint64_t>()((uint64_t(k.u) << 32 | k.v) ^ (uint64_t(uint32_t(k.vertex)) * 0x9E3779B97F4A7C15ull));
    }
  };
  std::unordered_map<WedgeKey, int, WedgeHash> sharedWedge;
  for (size_t f = 0; f < e.count; ++f) {
    corners.clear();
    wedgeUv.clear();
    for (size_t p = 0; p < e.properties.size(); ++p) {
      const Property& property = e.properties[p];
      if (!property.list) {
        (void)ENG_TRY_VALUE(body.next(property.type));
        continue;
      }
      const size_t n = ENG_TRY_VALUE(body.listLength(property.countType));
      for (size_t i = 0; i < n; ++i) {
        const double value = ENG_TRY_VALUE(body.next(property.type));
        if (int(p) == indices) {
          if (!(value >= 0 && value < double(out.positions.size())) || value != std::floor(value))
            return plyError(path, "face " + std::to_string(f) + " names vertex " + std::to_string(value) + " of " +
                                      std::to_string(out.positions.size()));
          corners.push_back(int(value));
        } else if (int(p) == wedges) {
          const float uv = std::isfinite(narrow(value)) ? narrow(value) : 0.0f;
          if (i % 2 == 0) wedgeUv.emplace_back(uv, 0.0f);
          else wedgeUv.back().y = uv;
        }
      }
    }
    if (corners.size() < 3) continue;  // points and edges: nothing to draw
    const bool wedgesHere = wedges >= 0 && wedgeUv.size() == corners.size();
    for (size_t k = 0; k < corners.size(); ++k) {
      int vt = vertexUvs ? corners[k] : -1;
      if (wedgesHere) {
        const WedgeKey key{corners[k], std::bit_cast<uint32_t>(wedgeUv[k].x), std::bit_cast<uint32_t>(wedgeUv[k].y)};
        const auto [it, added] = sharedWedge.try_emplace(key, int(out.texcoords.size()));
        if (added) out.texcoords.push_back(wedgeUv[k]);
        vt = it->second;
      }
      out.corners.push_back({corners[k], vt, vertexNormals ? corners[k] : -1});
    }
    out.faceStart.push_back(uint32_t(out.corners.size()));
    out.faceMaterial.push_back(material);
  }
  return {};
}

eng::Result<void> skipElement(BodyReader& body, const Element& e) {
  for (size_t r = 0; r < e.count; ++r)
    for (const Property& property : e.properties) {
      const size_t n = property.list ? ENG_TRY_VALUE(body.listLength(property.countType)) : 1;
      for (size_t i = 0; i < n; ++i) (void)ENG_TRY_VALUE(body.next(property.type));
    }
  return {};
}

}  // namespace

bool looksLikePly(std::span<const uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 5));
  return text.starts_with("ply\n") || text.starts_with("ply\r\n");
}

eng::Result<ObjPolygonMesh> readPlyPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  const Header header = ENG_TRY_VALUE(readHeader(bytes, path));
  BodyReader body(bytes, header, path);
  // Every record takes at least a byte (two characters in ASCII): a count
  // the bytes cannot hold is refused before anything is read for it, and an
  // element without properties (nothing to read, a loop of billions) as well.
  size_t least = 0;
  for (const Element& e : header.elements) {
    if (e.count > 0 && e.properties.empty()) return plyError(path, "element '" + eng::shownText(e.name) + "' has records but no properties");
    least += std::min(e.count, bytes.size()) * e.properties.size();
    if (!body.roomFor(least))
      return plyError(path, "element '" + eng::shownText(e.name) + "' claims " + std::to_string(e.count) + " records of " +
                                std::to_string(e.properties.size()) + " values; the file has " +
                                std::to_string(bytes.size() - header.bodyStart) + " bytes after its header");
  }
  const auto named = [&](std::string_view name) {
    return std::any_of(header.elements.begin(), header.elements.end(), [&](const Element& e) { return e.name == name && e.count > 0; });
  };
  if (!named("vertex")) return plyError(path, "no vertices");
  if (!named("face")) return plyError(path, "no faces (a point cloud: a face needs a surface)");

  ObjPolygonMesh out;
  out.faceStart.push_back(0);
  int material = -1;
  if (!header.textureFile.empty()) {
    ObjMaterial textured;
    textured.name = "TextureFile";
    auto resolved = eng::resolveInsideFolder(path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path(),
                                             header.textureFile);
    if (resolved) textured.diffuseTexture = *resolved;
    else out.warnings.push_back("texture '" + eng::shownText(header.textureFile) + "' is outside the PLY's folder; ignored");
    out.materials.push_back(std::move(textured));
    material = 0;
  }
  bool verticesRead = false;
  for (const Element& e : header.elements) {
    if (e.name == "vertex" && !verticesRead) {
      ENG_TRY(readVertices(body, e, out, path));
      verticesRead = true;
    } else if (e.name == "face" && verticesRead) {
      ENG_TRY(readFaces(body, e, out, material, path));
    } else if (e.name == "face") {
      return plyError(path, "its faces come before its vertices");
    } else {
      ENG_TRY(skipElement(body, e));
    }
  }
  if (out.faceCount() == 0) return plyError(path, "no faces of three or more corners");
  return out;
}

}  // namespace importers
