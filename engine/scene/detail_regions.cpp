#include "engine/scene/detail_regions.h"

#include <algorithm>
#include <cmath>

#include "engine/scene/model.h"

namespace eng {
namespace {

// Grows a 0/1 mask by `r` texels (a square), wrapping like a repeating texture.
std::vector<uint8_t> grow(const std::vector<uint8_t>& mask, int width, int height, int r) {
  std::vector<uint8_t> rows(mask.size(), 0), out(mask.size(), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!mask[size_t(y) * size_t(width) + size_t(x)]) continue;
      for (int dx = -r; dx <= r; ++dx) rows[size_t(y) * size_t(width) + size_t(((x + dx) % width + width) % width)] = 1;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!rows[size_t(y) * size_t(width) + size_t(x)]) continue;
      for (int dy = -r; dy <= r; ++dy) out[size_t(((y + dy) % height + height) % height) * size_t(width) + size_t(x)] = 1;
    }
  return out;
}

}  // namespace

DetailRegions::DetailRegions(std::span<const Image* const> layers) {
  for (const Image* image : layers) {
    Mask& mask = masks_.emplace_back();
    if (!image || image->width <= 0 || image->height <= 0 ||
        image->rgba8.size() != size_t(image->width) * size_t(image->height) * 4)
      continue;  // unknown: everywhere
    std::vector<uint8_t> painted(size_t(image->width) * size_t(image->height));
    for (size_t i = 0; i < painted.size(); ++i) painted[i] = image->rgba8[i * 4 + 3] > 0;
    mask.width = image->width;
    mask.height = image->height;
    mask.texels = grow(painted, image->width, image->height, kDetailRegionMargin);
  }
}

uint32_t DetailRegions::layersOver(glm::vec2 a, glm::vec2 b, glm::vec2 c) const {
  uint32_t layers = 0;
  for (size_t l = 0; l < masks_.size() && l < 32; ++l) {
    const Mask& mask = masks_[l];
    if (mask.width == 0) {
      layers |= 1u << l;
      continue;
    }
    // The footprint on a barycentric grid at most two texels apart (the
    // margin covers the gaps); beyond 64 a side, the layer is assumed to show.
    const glm::vec2 size(float(mask.width), float(mask.height));
    const glm::vec2 ta = a * size, tb = b * size, tc = c * size;
    const float longest = std::max({glm::length(tb - ta), glm::length(tc - tb), glm::length(ta - tc)});
    const int k = std::isfinite(longest) ? int(std::ceil(longest * 0.5f)) : 65;
    if (k > 64) {
      layers |= 1u << l;
      continue;
    }
    const auto wrap = [](float v, int n) { return ((int(std::floor(v)) % n) + n) % n; };
    bool hit = false;
    for (int i = 0; i <= std::max(k, 1) && !hit; ++i)
      for (int j = 0; i + j <= std::max(k, 1) && !hit; ++j) {
        const float s = float(i) / float(std::max(k, 1)), t = float(j) / float(std::max(k, 1));
        const glm::vec2 p = ta + (tb - ta) * s + (tc - ta) * t;
        hit = mask.texels[size_t(wrap(p.y, mask.height)) * size_t(mask.width) + size_t(wrap(p.x, mask.width))] != 0;
      }
    if (hit) layers |= 1u << l;
  }
  return layers;
}

DetailRuns DetailRegions::runsOf(std::span<const uint32_t> indices, std::span<const glm::vec2> texcoords) const {
  const size_t triangles = indices.size() / 3;
  std::vector<uint32_t> masks(triangles, 0);
  const uint32_t all = masks_.size() >= 32 ? ~0u : (1u << masks_.size()) - 1u;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    masks[t] = std::max({a, b, c}) < texcoords.size() ? layersOver(texcoords[a], texcoords[b], texcoords[c]) : all;
  }
  std::vector<uint32_t> order(triangles);
  for (uint32_t t = 0; t < triangles; ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return masks[x] < masks[y]; });
  DetailRuns runs;
  runs.indices.reserve(triangles * 3);
  for (const uint32_t t : order) {
    if (runs.runs.empty() || runs.runs.back().layerMask != masks[t])
      runs.runs.push_back({uint32_t(runs.indices.size()), 0, masks[t]});
    runs.indices.insert(runs.indices.end(), indices.begin() + std::ptrdiff_t(3 * t), indices.begin() + std::ptrdiff_t(3 * t + 3));
    runs.runs.back().indexCount += 3;
  }
  return runs;
}

}  // namespace eng
