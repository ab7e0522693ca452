// Quality tiers: names parse, each tier renders what it promises (sample
// count, shadow or none) under validation, and every tier draws the same
// lit sphere in the same place (a cheaper tier must not lose the subject).
#include "engine/vk/draw/render_quality.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/vk/draw/offscreen_renderer.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

TEST(RenderQuality, NamesRoundTripAndJunkIsRefused) {
  for (auto q : {eng::vk::RenderQuality::Fast, eng::vk::RenderQuality::Balanced, eng::vk::RenderQuality::High})
    EXPECT_EQ(eng::vk::renderQualityFromName(eng::vk::renderQualityName(q)), q);
  EXPECT_FALSE(eng::vk::renderQualityFromName("ultra"));
  EXPECT_FALSE(eng::vk::renderQualityFromName(""));
}

TEST(RenderQuality, TiersTradeSamplesShadowsAndHighlights) {
  const auto fast = eng::vk::qualitySettings(eng::vk::RenderQuality::Fast);
  const auto balanced = eng::vk::qualitySettings(eng::vk::RenderQuality::Balanced);
  const auto high = eng::vk::qualitySettings(eng::vk::RenderQuality::High);
  EXPECT_EQ(high.samples, VK_SAMPLE_COUNT_4_BIT);
  EXPECT_LT(balanced.samples, high.samples);
  EXPECT_EQ(fast.samples, VK_SAMPLE_COUNT_1_BIT);
  EXPECT_GT(high.shadowMapSize, 0u);
  EXPECT_EQ(balanced.shadowMapSize, high.shadowMapSize);
  EXPECT_EQ(fast.shadowMapSize, 0u);
  EXPECT_TRUE(high.secondarySpecular);
  EXPECT_FALSE(fast.secondarySpecular);
  // The edge-aware pass stands in for multisampling where balanced gets 1x.
  EXPECT_TRUE(balanced.edgeAntialias);
  EXPECT_FALSE(high.edgeAntialias);
  EXPECT_FALSE(fast.edgeAntialias);
}

eng::Image renderTier(eng::vk::RenderQuality quality, const eng::vk::SceneView& view, const eng::Model& model,
                      VkSampleCountFlagBits& samples) {
  auto renderer = eng::vk::OffscreenRenderer::create(vk_test::context(), {.width = 96, .height = 96, .quality = quality});
  EXPECT_TRUE(renderer) << (renderer ? "" : renderer.error().message);
  if (!renderer) return {};
  samples = renderer->samples();
  EXPECT_EQ(renderer->quality(), quality);
  auto gpu = renderer->upload(model);
  EXPECT_TRUE(gpu) << (gpu ? "" : gpu.error().message);
  if (!gpu) return {};
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  auto image = renderer->render(view, {&instance, 1});
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  return image ? std::move(image).value() : eng::Image{};
}

TEST(RenderQuality, EveryTierDrawsTheSameLitSubject) {
  const eng::Model model = testing_support::makeSphereModel({});
  const eng::vk::SceneView view{eng::OrbitCamera::frame(model.bounds()), {}};
  VkSampleCountFlagBits highSamples{}, balancedSamples{}, fastSamples{};
  const eng::Image high = renderTier(eng::vk::RenderQuality::High, view, model, highSamples);
  const eng::Image balanced = renderTier(eng::vk::RenderQuality::Balanced, view, model, balancedSamples);
  const eng::Image fast = renderTier(eng::vk::RenderQuality::Fast, view, model, fastSamples);
  ASSERT_EQ(high.width, 96);
  ASSERT_EQ(fast.width, 96);
  ASSERT_EQ(balanced.width, 96);
  EXPECT_EQ(fastSamples, VK_SAMPLE_COUNT_1_BIT);
  EXPECT_LE(balancedSamples, highSamples);
  // Same subject, same light: the centre pixel (lit sphere) agrees within a
  // shading term's worth, and the silhouettes cover the same area.
  const glm::ivec4 centreHigh = vk_test::pixel(high, 48, 48), centreFast = vk_test::pixel(fast, 48, 48);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(centreHigh[c], centreFast[c], 40) << "channel " << c;
  int differing = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const glm::ivec4 a = vk_test::pixel(high, x, y), b = vk_test::pixel(balanced, x, y);
      if (std::abs(a.r - b.r) > 16 || std::abs(a.g - b.g) > 16 || std::abs(a.b - b.b) > 16) ++differing;
    }
  // balanced differs from high only in edge antialiasing: a thin rim at most.
  EXPECT_LT(differing, 96 * 96 / 20) << "pixels of balanced off by more than 16/255 from high";
}

}  // namespace
