#include "tests/common/obj_test_files.h"

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

}  // namespace testing_support
