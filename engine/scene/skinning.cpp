#include "engine/scene/skinning.h"

#include <cmath>
#include <string>
#include <vector>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/skeleton_pose.h"

namespace eng {

glm::mat4 vertexSkinMatrix(const Primitive& primitive, size_t vertex, std::span<const glm::mat4> jointMatrices) {
  const size_t sets = primitive.influenceSets();
  glm::mat4 sum(0.0f);
  float total = 0.0f;
  for (size_t s = 0; s < sets; ++s) {
    const glm::u16vec4 joints = primitive.joints[vertex * sets + s];
    const glm::vec4 weights = primitive.jointWeights[vertex * sets + s];
    for (int i = 0; i < 4; ++i) {
      if (weights[i] == 0.0f || joints[i] >= jointMatrices.size()) continue;
      sum += weights[i] * jointMatrices[joints[i]];
      total += weights[i];
    }
  }
  return total > 0.0f ? sum : glm::mat4(1.0f);
}

Result<void> SkinPrimitiveJob::Validate() const {
  if (!primitive) return makeError(ErrorKind::InvalidArgument, "SkinPrimitiveJob: no primitive");
  const size_t n = primitive->vertexCount();
  if (positions.size() != n)
    return makeError(ErrorKind::InvalidArgument, "SkinPrimitiveJob: positions has " + std::to_string(positions.size()) +
                                                     " entries, primitive has " + std::to_string(n) + " vertices");
  if (!normals.empty() && normals.size() != n)
    return makeError(ErrorKind::InvalidArgument, "SkinPrimitiveJob: normals has " + std::to_string(normals.size()) +
                                                     " entries, primitive has " + std::to_string(n) + " vertices");
  const size_t sets = primitive->influenceSets();
  if (primitive->joints.size() != n * sets || primitive->jointWeights.size() != n * sets)
    return makeError(ErrorKind::InvalidArgument, "SkinPrimitiveJob: primitive has " +
                                                     std::to_string(primitive->joints.size()) + " joint groups and " +
                                                     std::to_string(primitive->jointWeights.size()) +
                                                     " weight groups for " + std::to_string(n) + " vertices");
  return {};
}

bool SkinPrimitiveJob::Run() const {
  if (!Validate().ok()) return false;  // allocates only to describe a failure
  const size_t n = primitive->vertexCount();
  if (primitive->influenceSets() == 0) return true;
  for (size_t v = 0; v < n; ++v) {
    const glm::mat4 skin = vertexSkinMatrix(*primitive, v, jointMatrices);
    positions[v] = glm::vec3(skin * glm::vec4(positions[v], 1.0f));
    if (normals.empty()) continue;
    const glm::vec3 nrm = glm::mat3(skin) * normals[v];
    const float len2 = glm::dot(nrm, nrm);
    // Same guard as the morph reference: no direction rather than NaN.
    normals[v] = len2 > 1e-20f ? nrm * (1.0f / std::sqrt(len2)) : nrm;
  }
  return true;
}

bool skinPrimitiveCpu(const Primitive& primitive, std::span<const glm::mat4> jointMatrices,
                      std::span<glm::vec3> positions, std::span<glm::vec3> normals) {
  return SkinPrimitiveJob{&primitive, jointMatrices, positions, normals}.Run();
}

bool posePrimitiveCpu(const Model& model, int meshNode, const Primitive& primitive, std::span<const float> meshWeights,
                      std::span<const glm::mat4> world, std::span<glm::vec3> positions, std::span<glm::vec3> normals) {
  // Both jobs validate before the morph writes, so a failure leaves the outputs as they were.
  const SkinPrimitiveJob skinCheck{&primitive, {}, positions, normals};
  if (!skinCheck.Validate().ok()) return false;
  if (!morphPrimitiveCpu(primitive, meshWeights, positions, normals)) return false;
  const int skin = meshNode >= 0 && static_cast<size_t>(meshNode) < model.nodes.size() ? model.nodes[meshNode].skin : -1;
  if (skin < 0 || static_cast<size_t>(skin) >= model.skins.size() || primitive.influenceSets() == 0) return true;
  std::vector<glm::mat4> joints;
  skinJointMatrices(model.skins[skin], world, meshNode, joints);
  return skinPrimitiveCpu(primitive, joints, positions, normals);
}

}  // namespace eng
