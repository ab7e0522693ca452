#include "tests/common/test_face.h"

#include <gtest/gtest.h>

#include "engine/scene/gltf_writer.h"
#include "tests/common/test_support.h"

namespace cli_test {

eng::Model makeTestFace() {
  constexpr int kGrid = 17;  // vertices per side
  eng::Primitive prim;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      prim.positions.push_back({float(x) / (kGrid - 1) - 0.5f, float(y) / (kGrid - 1) - 0.5f, 0.0f});
      prim.normals.push_back({0.0f, 0.0f, 1.0f});
    }
  for (int y = 0; y + 1 < kGrid; ++y)
    for (int x = 0; x + 1 < kGrid; ++x) {
      const uint32_t i = uint32_t(y * kGrid + x);
      prim.indices.insert(prim.indices.end(), {i, i + 1, i + kGrid, i + 1, i + kGrid + 1, i + kGrid});
    }
  auto target = [&](auto moves) {
    eng::MorphTarget t;
    for (const glm::vec3& p : prim.positions) t.positions.push_back(moves(p));
    return t;
  };
  const glm::vec3 none{0.0f};
  prim.targets.push_back(target([&](glm::vec3 p) { return p.x < 0 && p.y < 0 ? glm::vec3(0, 0.1f, 0.3f) : none; }));
  prim.targets.push_back(target([&](glm::vec3 p) { return p.x > 0 && p.y < 0 ? glm::vec3(0, 0.1f, 0.3f) : none; }));
  prim.targets.push_back(target([&](glm::vec3 p) { return p.y > 0.25f ? glm::vec3(0, -0.1f, 0) : none; }));
  prim.targets.push_back(target([&](glm::vec3 p) { return p.y < -0.25f ? glm::vec3(0, -0.2f, 0) : none; }));
  prim.targets.push_back(target([&](glm::vec3 p) { return glm::vec3(0, 0, 0.05f * p.x); }));
  prim.material = 0;

  eng::Model model;
  eng::Mesh mesh;
  mesh.name = "face";
  mesh.primitives.push_back(std::move(prim));
  mesh.targetNames = {"AU12_LipCornerPuller_L", "AU12_LipCornerPuller_R", "AU4_BrowLowerer", "AU26_JawDrop",
                      "custom_shape"};
  mesh.defaultWeights = {0.0f, 0.0f, 0.3f, 0.0f, 0.4f};
  model.meshes.push_back(std::move(mesh));
  eng::Material material;
  material.name = "skin";
  material.baseColorFactor = {0.8f, 0.6f, 0.5f, 1.0f};
  material.doubleSided = true;
  model.materials.push_back(material);
  eng::Node node;
  node.name = "face";
  node.mesh = 0;
  model.nodes.push_back(node);
  model.roots = {0};
  return model;
}

std::filesystem::path writeTestFace(const std::string& name) {
  const std::filesystem::path path = testing_support::freshTempDir(name) / "test_face.glb";
  if (auto saved = eng::saveModel(makeTestFace(), path); !saved)
    ADD_FAILURE() << "cannot write the test face: " << saved.error().message;
  return path;
}

}  // namespace cli_test
