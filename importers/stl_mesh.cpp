#include "importers/stl_mesh.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/text_lines.h"

namespace importers {
namespace {

constexpr size_t kHeaderBytes = 84;  // 80 bytes of header, a 32-bit triangle count
constexpr size_t kTriangleBytes = 50;  // normal, three corners (12 floats), a 16-bit attribute

uint32_t readU32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

float readF32(const uint8_t* p) {
  const uint32_t bits = readU32(p);
  float f = 0.0f;
  std::memcpy(&f, &bits, 4);
  return f;
}

bool isBinaryStl(std::span<const uint8_t> bytes) {
  return bytes.size() >= kHeaderBytes && kHeaderBytes + size_t(readU32(&bytes[80])) * kTriangleBytes == bytes.size();
}

eng::Error stlError(const std::filesystem::path& path, const std::string& what) {
  return eng::makeError(eng::ErrorKind::Malformed, path.string() + ": " + what);
}

// Triangles' corners gathered, then those at exactly the same position made
// one vertex: sorted by their bits (n log n whatever the input; a hash could
// be made to collide by a crafted file), numbered in the order met.
class Welder {
 public:
  void add(const glm::vec3& p) { corners_.push_back(p + glm::vec3(0.0f)); }  // + 0: -0 becomes 0

  ObjPolygonMesh weld() {
    using Bits = std::array<uint32_t, 3>;
    auto bitsOf = [&](uint32_t c) {
      Bits b;
      std::memcpy(b.data(), &corners_[c], sizeof b);
      return b;
    };
    std::vector<uint32_t> order(corners_.size());
    for (uint32_t c = 0; c < order.size(); ++c) order[c] = c;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return std::make_pair(bitsOf(a), a) < std::make_pair(bitsOf(b), b); });
    // Each run of equal positions takes the vertex of its first corner in the file.
    std::vector<int> vertexOf(corners_.size(), -1);
    ObjPolygonMesh mesh;
    for (size_t k = 0; k < order.size(); ++k) {
      if (k > 0 && bitsOf(order[k]) == bitsOf(order[k - 1])) vertexOf[order[k]] = vertexOf[order[k - 1]];
      else vertexOf[order[k]] = -2 - int(order[k]);  // its first corner, numbered below
    }
    std::vector<int> number(corners_.size(), -1);
    mesh.faceStart.push_back(0);
    for (size_t c = 0; c < corners_.size(); ++c) {
      const int first = -2 - vertexOf[c];
      if (number[size_t(first)] < 0) {
        number[size_t(first)] = int(mesh.positions.size());
        mesh.positions.push_back(corners_[c]);
      }
      mesh.corners.push_back(ObjCorner{number[size_t(first)], -1, -1});
      if (mesh.corners.size() % 3 == 0) {
        mesh.faceStart.push_back(uint32_t(mesh.corners.size()));
        mesh.faceMaterial.push_back(-1);
      }
    }
    return mesh;
  }

 private:
  std::vector<glm::vec3> corners_;  // three per triangle
};

eng::Result<ObjPolygonMesh> readBinary(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  Welder welder;
  const size_t count = readU32(&bytes[80]);
  for (size_t t = 0; t < count; ++t) {
    const uint8_t* p = &bytes[kHeaderBytes + t * kTriangleBytes + 12];  // past the facet normal
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 v(readF32(p + 12 * k), readF32(p + 12 * k + 4), readF32(p + 12 * k + 8));
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        return stlError(path, "triangle " + std::to_string(t) + " has a corner that is not a finite number");
      welder.add(v);
    }
  }
  return welder.weld();
}

eng::Result<ObjPolygonMesh> readAscii(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  Welder welder;
  eng::TextLines lines(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  std::string_view line;
  std::vector<glm::vec3> facet;
  size_t skipped = 0;
  bool inFacet = false;
  while (lines.nextNonBlank(line)) {
    const std::string where = "line " + std::to_string(lines.number()) + ": ";
    if (line.starts_with("facet")) {
      if (inFacet) return stlError(path, where + "a facet inside a facet (no 'endfacet' before it)");
      inFacet = true;
      facet.clear();
    } else if (line.starts_with("vertex")) {
      if (!inFacet) return stlError(path, where + "a vertex outside any facet");
      glm::vec3 v(0.0f);
      const char* at = line.data() + 6;
      const char* end = line.data() + line.size();
      for (int k = 0; k < 3; ++k) {
        while (at < end && (*at == ' ' || *at == '\t')) ++at;
        const auto [next, ec] = std::from_chars(at, end, v[k]);
        if (ec != std::errc() || !std::isfinite(v[k]))
          return stlError(path, where + "'" + eng::shownText(line) + "' is not 'vertex' and three finite numbers");
        at = next;
      }
      facet.push_back(v);
    } else if (line.starts_with("endfacet")) {
      if (!inFacet) return stlError(path, where + "'endfacet' without a facet");
      inFacet = false;
      // Fanned, as a few writers put more than three corners in a loop.
      for (size_t k = 2; k < facet.size(); ++k)
        for (const glm::vec3& v : {facet[0], facet[k - 1], facet[k]}) welder.add(v);
      skipped += facet.size() < 3;
    } else if (!(line.starts_with("solid") || line.starts_with("endsolid") || line.starts_with("outer") || line.starts_with("endloop"))) {
      return stlError(path, where + "'" + eng::shownText(line) + "' is no STL statement");
    }
  }
  if (inFacet) return stlError(path, "the last facet has no 'endfacet' (the file is cut short)");
  ObjPolygonMesh mesh = welder.weld();
  if (skipped > 0) mesh.warnings.push_back(std::to_string(skipped) + " facet(s) with fewer than three corners skipped");
  return mesh;
}

}  // namespace

bool looksLikeStl(std::span<const uint8_t> bytes) {
  if (isBinaryStl(bytes)) return true;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 1024));
  return eng::trimmed(text).starts_with("solid") && text.find("facet") != std::string_view::npos;
}

eng::Result<ObjPolygonMesh> readStlPolygonMesh(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  auto mesh = isBinaryStl(bytes) ? readBinary(bytes, path) : readAscii(bytes, path);
  if (!mesh) return mesh.error();
  if (mesh->faceCount() == 0) return stlError(path, "no triangles");
  return mesh;
}

}  // namespace importers
