#include "engine/scene/mesh_lod.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <meshoptimizer.h>

#include "engine/scene/model.h"

namespace eng {

std::vector<LodLevel> buildLodChain(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                    const LodChainOptions& options, std::span<const uint8_t> keep) {
  std::vector<LodLevel> levels;
  if (positions.empty() || indices.size() / 3 < options.minTriangles) return levels;
  // The kept triangles apart: the simplifier sees only the others, to which
  // the outline they share is a border (locked).
  std::vector<uint32_t> kept, source;
  const bool flagged = keep.size() == indices.size() / 3;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::vector<uint32_t>& into = flagged && keep[t / 3] ? kept : source;
    into.insert(into.end(), indices.begin() + std::ptrdiff_t(t), indices.begin() + std::ptrdiff_t(t + 3));
  }
  const float* xyz = &positions[0].x;
  const float scale = meshopt_simplifyScale(xyz, positions.size(), sizeof(glm::vec3));
  if (!(scale > 0.0f)) return levels;
  // Each level simplifies the one before it (half the work of starting from
  // the full list every time); its error bound is the sum along the cascade.
  float relativeError = 0.0f;
  std::vector<uint32_t> out(source.size());
  for (uint32_t level = 0; level < options.maxLevels && !source.empty(); ++level) {
    const size_t target = size_t(float(source.size() / 3) * options.ratio) * 3;
    if (target < 3) break;
    float stepError = 0.0f;
    const size_t count = meshopt_simplify(out.data(), source.data(), source.size(), xyz, positions.size(),
                                          sizeof(glm::vec3), target, options.maxRelativeError - relativeError,
                                          meshopt_SimplifyLockBorder, &stepError);
    if (count == 0 || float(count + kept.size()) > float(source.size() + kept.size()) * options.keepBelow) break;
    relativeError += stepError;
    source.assign(out.begin(), out.begin() + std::ptrdiff_t(count));
    LodLevel lod{source, relativeError * scale};
    lod.indices.insert(lod.indices.end(), kept.begin(), kept.end());
    levels.push_back(std::move(lod));
    if ((count + kept.size()) / 3 < options.minTriangles / 4) break;
  }
  return levels;
}

namespace {

// The largest channel range of the texels on a barycentric grid over the
// triangle's texture footprint, about two texels apart (at most 32 a side).
int paintedRange(const Image& texture, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
  const glm::vec2 size(float(texture.width), float(texture.height));
  const glm::vec2 ta = a * size, tb = b * size, tc = c * size;
  const float longest = std::max({glm::length(tb - ta), glm::length(tc - tb), glm::length(ta - tc)});
  if (!std::isfinite(longest)) return 0;
  const int k = std::clamp(int(std::ceil(longest * 0.5f)), 1, 32);
  const auto wrap = [](float v, int n) { return ((int(std::floor(v)) % n) + n) % n; };
  std::array<int, 3> lo{255, 255, 255}, hi{0, 0, 0};
  for (int i = 0; i <= k; ++i)
    for (int j = 0; i + j <= k; ++j) {
      const glm::vec2 p = ta + (tb - ta) * (float(i) / float(k)) + (tc - ta) * (float(j) / float(k));
      const size_t texel = size_t(wrap(p.y, texture.height)) * size_t(texture.width) + size_t(wrap(p.x, texture.width));
      for (size_t ch = 0; ch < 3; ++ch) {
        lo[ch] = std::min<int>(lo[ch], texture.rgba8[texel * 4 + ch]);
        hi[ch] = std::max<int>(hi[ch], texture.rgba8[texel * 4 + ch]);
      }
    }
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

}  // namespace

std::vector<uint8_t> keptTriangles(std::span<const uint32_t> indices, std::span<const glm::vec2> texcoords,
                                   const Image* texture, std::span<const glm::vec4> colors,
                                   std::span<const glm::vec3> normals, size_t vertexCount,
                                   const KeptTriangleLimits& limits) {
  std::vector<uint8_t> flags(indices.size() / 3, 0);
  const bool textured = texture && texture->width > 0 && texture->height > 0 && texcoords.size() == vertexCount &&
                        texture->rgba8.size() == size_t(texture->width) * size_t(texture->height) * 4;
  const bool coloured = colors.size() == vertexCount, normalled = normals.size() == vertexCount;
  const float cosCrease = std::cos(glm::radians(limits.creaseDegrees));
  for (size_t t = 0; t < flags.size(); ++t) {
    const uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    if (std::max({a, b, c}) >= vertexCount) continue;
    if (normalled && std::min({glm::dot(normals[a], normals[b]), glm::dot(normals[b], normals[c]),
                               glm::dot(normals[c], normals[a])}) < cosCrease) {
      flags[t] = 1;
      continue;
    }
    if (coloured) {
      const glm::vec3 range = glm::vec3(glm::max(glm::max(colors[a], colors[b]), colors[c]) -
                                        glm::min(glm::min(colors[a], colors[b]), colors[c]));
      if (std::max({range.r, range.g, range.b}) > limits.paintedContrast) {
        flags[t] = 1;
        continue;
      }
    }
    if (textured && float(paintedRange(*texture, texcoords[a], texcoords[b], texcoords[c])) > limits.paintedContrast * 255.0f)
      flags[t] = 1;
  }
  return flags;
}

std::vector<uint8_t> keptTriangles(const Primitive& prim, const Image* texture, const KeptTriangleLimits& limits) {
  const size_t n = prim.positions.size();
  std::vector<uint8_t> kept = keptTriangles(prim.indices, prim.texcoords, texture, prim.colors, prim.normals, n, limits);
  std::vector<glm::vec3> posed(prim.normals.size());
  for (const MorphTarget& target : prim.targets) {
    if (target.normals.size() != prim.normals.size()) continue;
    for (size_t v = 0; v < posed.size(); ++v) {
      const glm::vec3 normal = prim.normals[v] + target.normals[v];
      const float length = glm::length(normal);
      posed[v] = length > 1e-6f ? normal / length : prim.normals[v];
    }
    const std::vector<uint8_t> creased = keptTriangles(prim.indices, {}, nullptr, {}, posed, n, limits);
    for (size_t t = 0; t < kept.size(); ++t) kept[t] |= creased[t];
  }
  return kept;
}

}  // namespace eng
