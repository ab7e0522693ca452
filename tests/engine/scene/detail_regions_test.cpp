// Runs of triangles by the detail layers that can show on them (eng::DetailRegions).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>

#include "engine/scene/detail_regions.h"
#include "engine/scene/model.h"

namespace {

// A 64x64 layer painted (alpha > 0) on texels x, y in [16, 24).
eng::Image paintedSquare() {
  eng::Image image{.name = "furrows", .width = 64, .height = 64};
  image.rgba8.assign(64 * 64 * 4, 0);
  for (int y = 16; y < 24; ++y)
    for (int x = 16; x < 24; ++x) image.rgba8[size_t(y * 64 + x) * 4 + 3] = 1;  // the faintest paint counts
  return image;
}

glm::vec2 texel(float x, float y) { return {x / 64.0f, y / 64.0f}; }

TEST(DetailRegions, ATriangleTakesTheLayersWhosePaintItsFootprintReaches) {
  const eng::Image square = paintedSquare();
  const std::array<const eng::Image*, 2> layers{&square, nullptr};
  const eng::DetailRegions regions(layers);
  // Over the paint; within the margin (4 texels off); well away (20 texels off).
  EXPECT_EQ(regions.layersOver(texel(18, 18), texel(22, 18), texel(20, 22)), 0b11u);
  EXPECT_EQ(regions.layersOver(texel(28, 18), texel(30, 18), texel(29, 20)), 0b11u);
  EXPECT_EQ(regions.layersOver(texel(44, 40), texel(50, 40), texel(47, 46)), 0b10u) << "a layer without a texture shows anywhere";
  // A large triangle whose corners miss the paint but whose inside covers it.
  EXPECT_EQ(regions.layersOver(texel(0, 0), texel(60, 0), texel(0, 60)) & 1u, 1u);
  // Wrapping: the square seen through uv + 1.
  EXPECT_EQ(regions.layersOver(texel(82, 82), texel(86, 82), texel(84, 86)) & 1u, 1u);
}

TEST(DetailRegions, RunsKeepEveryTriangleAndGroupThemByLayers) {
  const eng::Image square = paintedSquare();
  const std::array<const eng::Image*, 1> layers{&square};
  const eng::DetailRegions regions(layers);
  // A 8x8 grid of quads over the whole texture: those near the square reach its layer.
  std::vector<glm::vec2> uv;
  for (int y = 0; y <= 8; ++y)
    for (int x = 0; x <= 8; ++x) uv.push_back(texel(float(x) * 8.0f, float(y) * 8.0f));
  std::vector<uint32_t> indices;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) {
      const uint32_t a = y * 9 + x;
      indices.insert(indices.end(), {a, a + 1, a + 10, a, a + 10, a + 9});
    }
  const eng::DetailRuns runs = regions.runsOf(indices, uv);
  ASSERT_EQ(runs.indices.size(), indices.size());
  const auto triangles = [](const std::vector<uint32_t>& list) {
    std::multiset<std::array<uint32_t, 3>> out;
    for (size_t t = 0; t + 2 < list.size(); t += 3) out.insert({list[t], list[t + 1], list[t + 2]});
    return out;
  };
  EXPECT_EQ(triangles(runs.indices), triangles(indices)) << "the same triangles, corners in the same order";
  ASSERT_EQ(runs.runs.size(), 2u) << "none, then the furrows";
  EXPECT_EQ(runs.runs[0].layerMask, 0u);
  EXPECT_EQ(runs.runs[1].layerMask, 1u);
  EXPECT_EQ(runs.runs[0].firstIndex, 0u);
  EXPECT_EQ(runs.runs[1].firstIndex, runs.runs[0].indexCount);
  EXPECT_EQ(runs.runs[0].indexCount + runs.runs[1].indexCount, indices.size());
  EXPECT_GT(runs.runs[0].indexCount, runs.runs[1].indexCount) << "most of the grid is away from the paint";
  // Corners past the texture coordinates: the triangle may show every layer.
  const eng::DetailRuns stray = regions.runsOf(std::vector<uint32_t>{0, 1, 500}, uv);
  ASSERT_EQ(stray.runs.size(), 1u);
  EXPECT_EQ(stray.runs[0].layerMask, 1u);
}

}  // namespace
