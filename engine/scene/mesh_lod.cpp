#include "engine/scene/mesh_lod.h"

#include <meshoptimizer.h>

namespace eng {

std::vector<LodLevel> buildLodChain(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                    const LodChainOptions& options) {
  std::vector<LodLevel> levels;
  if (positions.empty() || indices.size() / 3 < options.minTriangles) return levels;
  const float* xyz = &positions[0].x;
  const float scale = meshopt_simplifyScale(xyz, positions.size(), sizeof(glm::vec3));
  if (!(scale > 0.0f)) return levels;
  // Each level simplifies the one before it (half the work of starting from
  // the full list every time); its error bound is the sum along the cascade.
  std::vector<uint32_t> source(indices.begin(), indices.end());
  float relativeError = 0.0f;
  std::vector<uint32_t> out(indices.size());
  for (uint32_t level = 0; level < options.maxLevels; ++level) {
    const size_t target = size_t(float(source.size() / 3) * options.ratio) * 3;
    if (target < 3) break;
    float stepError = 0.0f;
    const size_t count = meshopt_simplify(out.data(), source.data(), source.size(), xyz, positions.size(),
                                          sizeof(glm::vec3), target, options.maxRelativeError - relativeError,
                                          meshopt_SimplifyLockBorder, &stepError);
    if (count == 0 || float(count) > float(source.size()) * options.keepBelow) break;
    relativeError += stepError;
    source.assign(out.begin(), out.begin() + std::ptrdiff_t(count));
    levels.push_back({source, relativeError * scale});
    if (count / 3 < options.minTriangles / 4) break;
  }
  return levels;
}

}  // namespace eng
