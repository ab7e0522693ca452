#include "engine/scene/cpu_morph.h"

#include <algorithm>
#include <cmath>

namespace eng {

Result<void> MorphPrimitiveJob::Validate() const {
  if (!primitive) return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: no primitive");
  const size_t n = primitive->vertexCount();
  if (weights.size() != primitive->targets.size())
    return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: " + std::to_string(weights.size()) +
                                                     " weights for " + std::to_string(primitive->targets.size()) +
                                                     " targets");
  if (outPositions.size() != n)
    return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: outPositions has " +
                                                     std::to_string(outPositions.size()) + " entries, primitive has " +
                                                     std::to_string(n) + " vertices");
  if (!outNormals.empty() && outNormals.size() != n)
    return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: outNormals has " +
                                                     std::to_string(outNormals.size()) + " entries, primitive has " +
                                                     std::to_string(n) + " vertices");
  if (!outNormals.empty() && primitive->normals.size() != n)
    return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: primitive has " +
                                                     std::to_string(primitive->normals.size()) + " normals for " +
                                                     std::to_string(n) + " vertices");
  for (size_t t = 0; t < weights.size(); ++t) {
    if (!std::isfinite(weights[t]))
      return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: weight " + std::to_string(t) + " is not finite");
    const MorphTarget& target = primitive->targets[t];
    if ((!target.positions.empty() && target.positions.size() != n) ||
        (!target.normals.empty() && target.normals.size() != n))
      return makeError(ErrorKind::InvalidArgument, "MorphPrimitiveJob: target " + std::to_string(t) +
                                                       " has deltas for another vertex count than " +
                                                       std::to_string(n));
  }
  return {};
}

bool MorphPrimitiveJob::Run() const {
  if (!Validate().ok()) return false;  // allocates only to describe a failure
  const Primitive& p = *primitive;
  const size_t n = p.vertexCount();
  const bool doNormals = !outNormals.empty();
  std::copy(p.positions.begin(), p.positions.end(), outPositions.begin());
  if (doNormals) std::copy(p.normals.begin(), p.normals.end(), outNormals.begin());

  for (size_t t = 0; t < p.targets.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = p.targets[t];
    if (!target.positions.empty())
      for (size_t v = 0; v < n; ++v) outPositions[v] += w * target.positions[v];
    if (doNormals && !target.normals.empty())
      for (size_t v = 0; v < n; ++v) outNormals[v] += w * target.normals[v];
  }
  if (doNormals) {
    for (glm::vec3& nrm : outNormals) {
      const float len2 = glm::dot(nrm, nrm);
      // A normal blended to (near) zero has no direction; keep it as is rather than make NaNs.
      if (len2 > 1e-20f) nrm *= 1.0f / std::sqrt(len2);
    }
  }
  return true;
}

bool morphPrimitiveCpu(const Primitive& primitive, std::span<const float> meshWeights,
                       std::span<glm::vec3> outPositions, std::span<glm::vec3> outNormals) {
  return MorphPrimitiveJob{&primitive, meshWeights, outPositions, outNormals}.Run();
}

}  // namespace eng
