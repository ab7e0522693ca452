#include "tests/common/obj_test_files.h"
#include "tests/common/placed_primitive.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace testing_support {

glm::vec3 GridObj::rest(int index) const {
  return glm::vec3(static_cast<float>(index % (nx + 1)), static_cast<float>(index / (nx + 1)), 0.0f);
}

std::string GridObj::text() const {
  const char* eol = crlf ? "\r\n" : "\n";
  const int n = vertexCount();
  std::vector<int> fileOrder = order;
  if (fileOrder.empty())
    for (int i = 0; i < n; ++i) fileOrder.push_back(i);
  std::vector<int> lineOf(n);  // 1-based OBJ index of each grid vertex
  for (int k = 0; k < n; ++k) lineOf[fileOrder[k]] = k + 1;

  std::ostringstream out;
  out.precision(9);
  out << "# grid " << nx << "x" << ny << eol;
  if (!material.empty()) out << "mtllib " << material << ".mtl" << eol;
  for (int k = 0; k < n; ++k) {
    const int i = fileOrder[k];
    const glm::vec3 p = position ? position(i, rest(i)) : rest(i);
    out << "v " << p.x << " " << p.y << " " << p.z << eol;
  }
  if (texcoords)
    for (int k = 0; k < n; ++k) {
      const glm::vec3 r = rest(fileOrder[k]);
      out << "vt " << r.x / nx << " " << r.y / ny << eol;
    }
  if (normals)
    for (int k = 0; k < n; ++k) {
      const glm::vec3 nn = normal ? normal(fileOrder[k]) : glm::vec3(0, 0, 1);
      out << "vn " << nn.x << " " << nn.y << " " << nn.z << eol;
    }
  if (!material.empty()) out << "usemtl " << material << eol;
  auto corner = [&](int i) {
    const int l = lineOf[i];
    std::string s = std::to_string(l);
    if (texcoords || normals) s += "/" + (texcoords ? std::to_string(l) : std::string());
    if (normals) s += "/" + std::to_string(l);
    return s;
  };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int a = y * (nx + 1) + x, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      if (quads) {
        out << "f " << corner(a) << " " << corner(b) << " " << corner(c) << " " << corner(d) << eol;
      } else {
        out << "f " << corner(a) << " " << corner(b) << " " << corner(c) << eol;
        out << "f " << corner(a) << " " << corner(c) << " " << corner(d) << eol;
      }
    }
  return out.str();
}

std::string modelAsObj(const eng::Model& model, const std::string& header) {
  std::string text = header;
  char line[160];
  size_t base = 1;
  forEachPlacedPrimitive(model, [&](const PlacedPrimitive& placed) {
    const eng::Primitive& p = placed.primitive;
    text += "o " + placed.meshName + "_" + std::to_string(base) + "\n";
    for (const glm::vec3& w : placed.positions) {
      std::snprintf(line, sizeof line, "v %.7g %.7g %.7g\n", double(w.x), double(w.y), double(w.z));
      text += line;
    }
    for (size_t v = 0; v < p.positions.size(); ++v) {
      const glm::vec2 uv = v < p.texcoords.size() ? p.texcoords[v] : glm::vec2(0.0f);
      std::snprintf(line, sizeof line, "vt %.7g %.7g\n", double(uv.x), double(1.0f - uv.y));
      text += line;
    }
    for (const glm::vec3& nrm : placed.normals) {
      std::snprintf(line, sizeof line, "vn %.7g %.7g %.7g\n", double(nrm.x), double(nrm.y), double(nrm.z));
      text += line;
    }
    for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
      const size_t a = base + p.indices[i], b = base + p.indices[i + 1], c = base + p.indices[i + 2];
      std::snprintf(line, sizeof line, "f %zu/%zu/%zu %zu/%zu/%zu %zu/%zu/%zu\n", a, a, a, b, b, b, c, c, c);
      text += line;
    }
    base += p.positions.size();
  });
  return text;
}

std::string modelAsPly(const eng::Model& model) {
  std::vector<float> vertices;  // x y z nx ny nz
  std::vector<uint32_t> triangles;
  forEachPlacedPrimitive(model, [&](const PlacedPrimitive& placed) {
    const uint32_t base = uint32_t(vertices.size() / 6);
    for (size_t v = 0; v < placed.positions.size(); ++v) {
      const glm::vec3 &w = placed.positions[v], &nrm = placed.normals[v];
      vertices.insert(vertices.end(), {w.x, w.y, w.z, nrm.x, nrm.y, nrm.z});
    }
    for (uint32_t i : placed.primitive.indices) triangles.push_back(base + i);
  });
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment a head scan\nelement vertex " +
                    std::to_string(vertices.size() / 6) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                    "element face " + std::to_string(triangles.size() / 3) +
                    "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.append(reinterpret_cast<const char*>(vertices.data()), vertices.size() * sizeof(float));
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    out.push_back('\3');
    out.append(reinterpret_cast<const char*>(&triangles[t]), 3 * sizeof(uint32_t));
  }
  return out;
}

std::string modelAsStl(const eng::Model& model, const std::string& header) {
  std::string out = header.substr(0, 80);
  out.resize(84, '\0');
  uint32_t count = 0;
  forEachPlacedPrimitive(model, [&](const PlacedPrimitive& placed) {
    const std::vector<uint32_t>& indices = placed.primitive.indices;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      float record[12] = {};  // the facet normal left zero, as many exporters write it
      for (int k = 0; k < 3; ++k) std::memcpy(&record[3 + 3 * k], &placed.positions[indices[t + size_t(k)]], sizeof(glm::vec3));
      out.append(reinterpret_cast<const char*>(record), sizeof record);
      out.append(2, '\0');
      ++count;
    }
  });
  std::memcpy(&out[80], &count, 4);
  return out;
}

}  // namespace testing_support
