// The edge-aware anti-aliasing pass of a 1-sample offscreen target: where
// there is no edge the bytes read back are the ones the plain target reads
// back; a hard edge gets intermediate values along it, a stair-stepped one
// a blend across each step; and the validation layer stays quiet (the test
// context fails on any message).
#include "engine/vk/draw/edge_antialias.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "engine/vk/draw/offscreen_renderer.h"
#include "engine/vk/draw/offscreen_target.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

float srgbToLinear(int byte) {
  const float c = float(byte) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// A rectangle of one sRGB colour (opaque), drawn by clearing it.
struct ColourRect {
  VkRect2D rect;
  std::array<int, 3> srgb;
};

const eng::vk::EdgeAntialiasPipeline& antialiasPipeline() {
  static const eng::vk::EdgeAntialiasPipeline pipeline = [] {
    auto made = eng::vk::EdgeAntialiasPipeline::create(vk_test::context(), eng::vk::ShaderLibrary(),
                                                       VK_FORMAT_R8G8B8A8_SRGB);
    if (!made) {
      ADD_FAILURE() << made.error().message;
      std::abort();
    }
    return std::move(made).value();
  }();
  return pipeline;
}

// A 1-sample target of `width` x `height` with the rectangles cleared into
// it, read back with or without the anti-aliasing pass.
eng::Image render(uint32_t width, uint32_t height, const std::vector<ColourRect>& rects, bool antialias) {
  auto target = eng::vk::OffscreenTarget::create(vk_test::context(), width, height, VK_SAMPLE_COUNT_1_BIT,
                                                 antialias ? &antialiasPipeline() : nullptr);
  EXPECT_TRUE(target) << (target ? "" : target.error().message);
  if (!target) return {};
  EXPECT_EQ(target->edgeAntialiased(), antialias);
  auto drawn = target->render({{},
                               [&](VkCommandBuffer cmd) {
                                 for (const ColourRect& r : rects) {
                                   VkClearAttachment clear{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
                                   clear.clearValue.color = {{srgbToLinear(r.srgb[0]), srgbToLinear(r.srgb[1]),
                                                              srgbToLinear(r.srgb[2]), 1.0f}};
                                   const VkClearRect area{r.rect, 0, 1};
                                   vkCmdClearAttachments(cmd, 1, &clear, 1, &area);
                                 }
                               },
                               {}});
  EXPECT_TRUE(drawn) << (drawn ? "" : drawn.error().message);
  return target->readPixels();
}

int channel(const eng::Image& image, int x, int y, int c) {
  return image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4 + size_t(c)];
}

TEST(EdgeAntialias, ImageWithoutEdgesComesBackUnchanged) {
  // 256 columns, each one sRGB level from its neighbours in every channel:
  // far below the pass's contrast threshold, so nothing is an edge.
  std::vector<ColourRect> columns;
  for (int x = 0; x < 256; ++x)
    columns.push_back({{{x, 0}, {1, 8}}, {x, 255 - x, x / 2}});
  const eng::Image plain = render(256, 8, columns, false);
  const eng::Image filtered = render(256, 8, columns, true);
  ASSERT_EQ(plain.rgba8.size(), filtered.rgba8.size());
  ASSERT_FALSE(plain.rgba8.empty());
  int worst = 0;
  for (size_t i = 0; i < plain.rgba8.size(); ++i) worst = std::max(worst, std::abs(plain.rgba8[i] - filtered.rgba8[i]));
  EXPECT_LE(worst, 1) << "largest difference from the plain 1x image, in 1/255";
  EXPECT_EQ(channel(plain, 200, 4, 0), 200);  // the clears encode to the levels asked for
}

TEST(EdgeAntialias, HardVerticalEdgeGetsIntermediateValuesAlongIt) {
  const std::vector<ColourRect> halves{{{{0, 0}, {32, 64}}, {0, 0, 0}}, {{{32, 0}, {32, 64}}, {255, 255, 255}}};
  const eng::Image plain = render(64, 64, halves, false);
  const eng::Image filtered = render(64, 64, halves, true);
  ASSERT_FALSE(filtered.rgba8.empty());
  for (int y = 4; y < 60; ++y) {
    SCOPED_TRACE("row " + std::to_string(y));
    EXPECT_EQ(channel(plain, 31, y, 1), 0);
    EXPECT_EQ(channel(plain, 32, y, 1), 255);
    EXPECT_GT(channel(filtered, 31, y, 1), 0);     // the dark side takes some of the light
    EXPECT_LT(channel(filtered, 32, y, 1), 255);   // and the light side some of the dark
    EXPECT_EQ(channel(filtered, 28, y, 1), 0);     // away from the edge: untouched
    EXPECT_EQ(channel(filtered, 36, y, 1), 255);
  }
}

TEST(EdgeAntialias, StairStepsBlendAcrossEachStep) {
  // A near-vertical edge one pixel further right every 8 rows: the 1x
  // stair-step. Near each step's ends the pass blends up to half a pixel.
  std::vector<ColourRect> rects{{{{0, 0}, {64, 64}}, {255, 255, 255}}};
  for (int step = 0; step < 8; ++step)
    rects.push_back({{{0, step * 8}, {uint32_t(24 + step), 8}}, {0, 0, 0}});
  const eng::Image filtered = render(64, 64, rects, true);
  ASSERT_FALSE(filtered.rgba8.empty());
  int midTones = 0;  // pixels well between black and white
  for (int y = 0; y < 64; ++y)
    for (int x = 20; x < 36; ++x) {
      const int g = channel(filtered, x, y, 1);
      if (g > 64 && g < 192) ++midTones;
    }
  EXPECT_GE(midTones, 16) << "of the 64 rows along the edge";
}

TEST(EdgeAntialias, MultisampledTargetIsResolvedAsBefore) {
  auto target = eng::vk::OffscreenTarget::create(vk_test::context(), 16, 16, VK_SAMPLE_COUNT_4_BIT,
                                                 &antialiasPipeline());
  ASSERT_TRUE(target) << target.error().message;
  EXPECT_EQ(target->edgeAntialiased(), target->format().samples == VK_SAMPLE_COUNT_1_BIT);
}

// The tier switch reaches the renderer's targets, and a filtered sequence
// with frames in flight gives the pictures single renders give.
TEST(EdgeAntialias, BalancedFiltersWhereTheDeviceGivesOneSample) {
  const eng::Model model = testing_support::makeSphereModel({});
  const eng::vk::SceneView view = vk_test::viewOf(model.bounds());
  auto high = eng::vk::OffscreenRenderer::create(vk_test::context(),
                                                 {.width = 64, .height = 64, .quality = eng::vk::RenderQuality::High});
  ASSERT_TRUE(high) << high.error().message;
  EXPECT_FALSE(high->edgeAntialiased());
  auto balanced = eng::vk::OffscreenRenderer::create(
      vk_test::context(),
      {.width = 64, .height = 64, .quality = eng::vk::RenderQuality::Balanced, .framesInFlight = 2});
  ASSERT_TRUE(balanced) << balanced.error().message;
  EXPECT_EQ(balanced->edgeAntialiased(), balanced->samples() == VK_SAMPLE_COUNT_1_BIT);
  auto gpu = balanced->upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  auto single = balanced->render(view, {&instance, 1});
  ASSERT_TRUE(single) << single.error().message;
  ASSERT_TRUE(balanced->submit(view, {&instance, 1}));
  ASSERT_TRUE(balanced->submit(view, {&instance, 1}));
  for (int frame = 0; frame < 2; ++frame) {
    auto collected = balanced->collect();
    ASSERT_TRUE(collected) << collected.error().message;
    EXPECT_EQ(collected->rgba8, single->rgba8) << "frame " << frame;
  }
}

}  // namespace
