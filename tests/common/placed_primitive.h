#pragma once
// What the scan-like writers (modelAsObj, modelAsPly, modelAsFbx) export.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace testing_support {

// A model at rest as a scan holds it: every mesh node's primitives, positions
// and normals in world space.
struct PlacedPrimitive {
  const std::string& meshName;
  const eng::Primitive& primitive;
  std::vector<glm::vec3> positions, normals;
};

template <typename Visit>
void forEachPlacedPrimitive(const eng::Model& model, Visit visit) {
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const eng::Node& node = model.nodes[n];
    if (node.mesh < 0) continue;
    const glm::mat4 world = model.worldTransform(int(n));
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (const eng::Primitive& p : model.meshes[size_t(node.mesh)].primitives) {
      PlacedPrimitive placed{model.meshes[size_t(node.mesh)].name, p, {}, {}};
      for (size_t v = 0; v < p.positions.size(); ++v) {
        placed.positions.emplace_back(world * glm::vec4(p.positions[v], 1.0f));
        placed.normals.push_back(v < p.normals.size() ? glm::normalize(normalMatrix * p.normals[v]) : glm::vec3(0, 0, 1));
      }
      visit(placed);
    }
  }
}

}  // namespace testing_support
