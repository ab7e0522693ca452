#include "engine/scene/detail_regions.h"

#include <algorithm>
#include <cmath>

#include "engine/scene/model.h"

namespace eng {
namespace {

int wrapIndex(int v, int n) { return ((v % n) + n) % n; }

// Marks out[x] where src has a 1 within `r` places either side of x, along a
// cyclic line of `n` entries `stride` apart (a running count over the line
// extended by r at each end: linear in n whatever r is).
void growLine(const uint8_t* src, uint8_t* out, int n, size_t stride, int r, std::vector<int>& counts) {
  const int extended = n + 2 * r;
  counts.assign(size_t(extended) + 1, 0);
  for (int i = 0; i < extended; ++i) counts[size_t(i) + 1] = counts[size_t(i)] + src[size_t(wrapIndex(i - r, n)) * stride];
  for (int x = 0; x < n; ++x) out[size_t(x) * stride] = counts[size_t(x) + size_t(2 * r) + 1] - counts[size_t(x)] > 0;
}

// Grows a 0/1 mask by `r` texels (a square), wrapping like a repeating texture.
std::vector<uint8_t> grow(const std::vector<uint8_t>& mask, int width, int height, int r) {
  std::vector<uint8_t> rows(mask.size(), 0), out(mask.size(), 0);
  std::vector<int> counts;
  for (int y = 0; y < height; ++y)
    growLine(&mask[size_t(y) * size_t(width)], &rows[size_t(y) * size_t(width)], width, 1, r, counts);
  for (int x = 0; x < width; ++x) growLine(&rows[size_t(x)], &out[size_t(x)], height, size_t(width), r, counts);
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
    mask.blocksWide = (mask.width + kBlock - 1) / kBlock;
    mask.blocks.assign(size_t(mask.blocksWide) * size_t((mask.height + kBlock - 1) / kBlock), 0);
    std::vector<int> set(mask.blocks.size(), 0), total(mask.blocks.size(), 0);
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        const size_t b = size_t(y / kBlock) * size_t(mask.blocksWide) + size_t(x / kBlock);
        ++total[b];
        set[b] += mask.texels[size_t(y) * size_t(mask.width) + size_t(x)];
      }
    for (size_t b = 0; b < mask.blocks.size(); ++b)
      mask.blocks[b] = set[b] == 0 ? kNone : set[b] == total[b] ? kAll : kSome;
  }
}

// kNone if no texel in [x0, x1] x [y0, y1] (inside the texture) is set, kAll
// if every one is, else kSome.
uint8_t DetailRegions::Mask::over(int x0, int y0, int x1, int y1) const {
  bool none = true, all = true;
  for (int by = y0 / kBlock; by <= y1 / kBlock; ++by)
    for (int bx = x0 / kBlock; bx <= x1 / kBlock; ++bx) {
      const uint8_t b = blocks[size_t(by) * size_t(blocksWide) + size_t(bx)];
      none = none && b == kNone;
      all = all && b == kAll;
    }
  return none ? kNone : all ? kAll : kSome;
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
    // Every sample lands in the footprint's texel box (a texel wider for
    // rounding): when the box lies inside the texture and its blocks are all
    // painted or all bare, that is the answer.
    const glm::vec2 lo = glm::min(ta, glm::min(tb, tc)) - 1.0f, hi = glm::max(ta, glm::max(tb, tc)) + 1.0f;
    if (lo.x >= 0.0f && lo.y >= 0.0f && hi.x < size.x && hi.y < size.y) {
      const uint8_t over = mask.over(int(lo.x), int(lo.y), int(hi.x), int(hi.y));
      if (over != kSome) {
        if (over == kAll) layers |= 1u << l;
        continue;
      }
    }
    const auto wrap = [](float v, int n) { return wrapIndex(int(std::floor(v)), n); };
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
