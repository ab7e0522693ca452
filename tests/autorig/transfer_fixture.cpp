#include "tests/autorig/transfer_fixture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "autorig/builtin_source.h"
#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace transfer_fixture {

std::optional<eng::Model> loadHead() {
  eng::Result<eng::Model> model = eng::loadModel(testing_support::sourceDir() / "data/head.glb");
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return std::nullopt;
  }
  return std::move(*model);
}

autorig::SourceFace headSource(const eng::Model& head) {
  eng::Result<autorig::SourceFace> source = autorig::builtInSource(head);
  if (!source) {
    ADD_FAILURE() << source.error().message;
    return {};
  }
  return std::move(*source);
}

float relativeError(const eng::Model& a, const eng::Model& b, const char* mesh, size_t primitive, const char* targetA,
                    const char* targetB) {
  auto find = [&](const eng::Model& model, const char* target) -> std::pair<const eng::Mesh*, size_t> {
    for (const eng::Mesh& m : model.meshes) {
      if (m.name != mesh) continue;
      auto it = std::find(m.targetNames.begin(), m.targetNames.end(), target);
      if (it != m.targetNames.end()) return {&m, size_t(it - m.targetNames.begin())};
    }
    return {nullptr, 0};
  };
  const auto [ma, ta] = find(a, targetA);
  const auto [mb, tb] = find(b, targetB);
  if (!ma || !mb) {
    ADD_FAILURE() << "no target " << (ma ? targetB : targetA) << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  float size = 0.0f, worst = 0.0f;
  if (primitive >= ma->primitives.size() || primitive >= mb->primitives.size()) {
    ADD_FAILURE() << "no primitive " << primitive << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  const std::vector<glm::vec3>& da = ma->primitives[primitive].targets[ta].positions;
  const std::vector<glm::vec3>& db = mb->primitives[primitive].targets[tb].positions;
  for (size_t v = 0; v < da.size() && v < db.size(); ++v) {
    size = std::max(size, glm::length(da[v]));
    worst = std::max(worst, glm::length(da[v] - db[v]));
  }
  return size > 0.0f ? worst / size : std::numeric_limits<float>::infinity();
}

}  // namespace transfer_fixture
