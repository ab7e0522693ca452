#include "tests/common/test_meshes.h"

#include <utility>

namespace testing_support {

eng::Primitive flatSheet(int side) {
  eng::Primitive p;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      p.positions.push_back({float(x) / float(side - 1) - 0.5f, float(y) / float(side - 1) - 0.5f, 0.0f});
      p.normals.push_back({0, 0, 1});
    }
  for (int y = 0; y + 1 < side; ++y)
    for (int x = 0; x + 1 < side; ++x) {
      const uint32_t a = uint32_t(y * side + x), b = a + 1, c = a + uint32_t(side), d = c + 1;
      p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
    }
  return p;
}

eng::Model singleMeshModel(eng::Mesh mesh, std::string sourcePath) {
  eng::Model model;
  model.sourcePath = std::move(sourcePath);
  model.meshes.push_back(std::move(mesh));
  eng::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  model.roots = {0};
  return model;
}

}  // namespace testing_support
