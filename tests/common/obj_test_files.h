#pragma once
// Small OBJ keyframe meshes written by the tests: a grid of quads (or
// triangles) with optional normals, texcoords, CRLF endings, displaced
// vertices and a shuffled vertex order; any model as one OBJ.
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace testing_support {

struct GridObj {
  int nx = 4, ny = 3;  // cells; (nx+1)*(ny+1) vertices
  bool quads = true;
  bool normals = true;
  bool texcoords = true;
  bool crlf = false;
  std::string material;  // "usemtl" name (with "mtllib <material>.mtl"), empty = none
  // Position of grid vertex i (default: (x, y, 0)); targets override it.
  std::function<glm::vec3(int index, glm::vec3 rest)> position;
  std::function<glm::vec3(int index)> normal;  // default (0, 0, 1)
  // File order of the vertices: line k holds grid vertex order[k] (empty = identity).
  std::vector<int> order;

  int vertexCount() const { return (nx + 1) * (ny + 1); }
  glm::vec3 rest(int index) const;
  std::string text() const;
};

// A model at rest as one OBJ file, as a scan arrives: every mesh node's
// primitives in world space (positions, texcoords, normals), one `o` each,
// no targets and no materials, after `header` (comment lines).
std::string modelAsObj(const eng::Model& model, const std::string& header = "");

// The same as one binary little-endian PLY file, as a scanner writes it:
// positions and normals in world space, one list of triangles.
std::string modelAsPly(const eng::Model& model);

// The same as one binary STL file, as a scanner exports it: every triangle
// with its own three corners (world space), `header` as its 80-byte header.
std::string modelAsStl(const eng::Model& model, const std::string& header = "binary STL written by the tests");

}  // namespace testing_support
