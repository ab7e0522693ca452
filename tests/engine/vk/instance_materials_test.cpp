// Per-instance material records (ModelInstance::materials): what an animation
// moves per frame (VRM material colour and texture transform binds) without
// touching the uploaded model. An override must draw exactly what a model
// with those values baked in draws (colour, emission, texture coordinates),
// instances of one model keep their own values in one instanced draw, and bad
// records are refused naming the instance.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/vk/draw/offscreen_renderer.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

using vk_test::pixel;
using vk_test::viewOf;

eng::Image renderOrFail(const eng::Aabb& bounds, std::span<const eng::vk::ModelInstance> instances) {
  auto image = vk_test::renderer().render(viewOf(bounds), instances);
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  return image ? std::move(image).value() : eng::Image{};
}

// Largest difference of any channel of any pixel.
int maxDifference(const eng::Image& a, const eng::Image& b) {
  if (a.rgba8.size() != b.rgba8.size() || a.rgba8.empty()) return 256;
  int worst = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) worst = std::max(worst, std::abs(int(a.rgba8[i]) - int(b.rgba8[i])));
  return worst;
}

// The sphere with a texture of 4 x 4 distinct colours, so a texture
// coordinate change shows.
eng::Model texturedSphere() {
  eng::Model model = testing_support::makeSphereModel({.targets = 0, .color = glm::vec4(1.0f)});
  eng::Image checker;
  checker.name = "checker";
  checker.width = checker.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      checker.rgba8.insert(checker.rgba8.end(), {uint8_t(40 + 60 * x), uint8_t(40 + 60 * y), uint8_t(200 - 40 * x), 255});
  model.images.push_back(checker);
  model.materials[0].baseColorImage = 0;
  return model;
}

// Renders `model` once with the material record `record` as an override and
// returns it with the same model rendered with the record baked into its
// material (bake edits the model before upload).
template <typename Bake>
std::pair<eng::Image, eng::Image> overrideAndBaked(const eng::Model& model, const eng::vk::InstanceMaterial& record,
                                                   Bake bake) {
  auto gpu = vk_test::renderer().upload(model);
  EXPECT_TRUE(gpu) << gpu.error().message;
  if (!gpu) return {};
  EXPECT_EQ(gpu->materialCount(), 1u);
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance overridden{&*gpu, glm::mat4(1.0f), weights, {}, {&record, 1}};
  eng::Image viaOverride = renderOrFail(model.bounds(), {&overridden, 1});

  eng::Model baked = model;
  bake(baked);
  auto bakedGpu = vk_test::renderer().upload(baked);
  EXPECT_TRUE(bakedGpu) << bakedGpu.error().message;
  if (!bakedGpu) return {};
  const eng::vk::ModelInstance plain{&*bakedGpu, glm::mat4(1.0f), weights};
  return {std::move(viaOverride), renderOrFail(model.bounds(), {&plain, 1})};
}

TEST(InstanceMaterials, ColourAndEmissionOverridesDrawLikeBakedMaterials) {
  const eng::Model model = testing_support::makeSphereModel({.color = glm::vec4(0.8f, 0.6f, 0.5f, 1.0f)});
  eng::vk::InstanceMaterial record;
  record.baseColorFactor = glm::vec4(0.9f, 0.1f, 0.1f, 1.0f);
  record.emissive = glm::vec4(0.0f, 0.05f, 0.2f, 0.0f);
  const auto [viaOverride, baked] = overrideAndBaked(model, record, [&](eng::Model& m) {
    m.materials[0].baseColorFactor = record.baseColorFactor;
    m.materials[0].emissiveFactor = glm::vec3(record.emissive);
  });
  EXPECT_LE(maxDifference(viaOverride, baked), 1);
  const glm::ivec4 centre = pixel(viaOverride, 128, 128);
  EXPECT_GT(centre.r, centre.g + 60) << "the override's red, not the material's skin tone";
}

TEST(InstanceMaterials, TextureTransformOverrideDrawsLikeTransformedTexcoords) {
  const eng::Model model = texturedSphere();
  eng::vk::InstanceMaterial record;
  record.uvTransform = glm::vec4(0.5f, 2.0f, 0.25f, 0.1f);  // uv * (0.5, 2) + (0.25, 0.1)
  const auto [viaOverride, baked] = overrideAndBaked(model, record, [&](eng::Model& m) {
    for (glm::vec2& uv : m.meshes[0].primitives[0].texcoords)
      uv = uv * glm::vec2(record.uvTransform) + glm::vec2(record.uvTransform.z, record.uvTransform.w);
  });
  EXPECT_LE(maxDifference(viaOverride, baked), 2);
  // And it did move the texture: the untransformed sphere looks different.
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance plain{&*gpu, glm::mat4(1.0f), weights};
  EXPECT_GT(maxDifference(renderOrFail(model.bounds(), {&plain, 1}), viaOverride), 40);
}

TEST(InstanceMaterials, InstancesOfOneModelKeepTheirOwnRecords) {
  const eng::Model model = testing_support::makeSphereModel({.color = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f)});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  ASSERT_EQ(gpu->materials().size(), 2u) << "the model's material, then the default material";
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  eng::vk::InstanceMaterial red = gpu->materials()[0], blue = gpu->materials()[0];
  red.baseColorFactor = glm::vec4(1.0f, 0.05f, 0.05f, 1.0f);
  blue.baseColorFactor = glm::vec4(0.05f, 0.05f, 1.0f, 1.0f);
  const std::vector<eng::vk::ModelInstance> instances{
      {&*gpu, glm::translate(glm::mat4(1.0f), glm::vec3(-1.2f, 0.0f, 0.0f)), weights, {}, {&red, 1}},
      {&*gpu, glm::mat4(1.0f), weights},  // the model's own grey
      {&*gpu, glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.0f, 0.0f)), weights, {}, {&blue, 1}},
  };
  const eng::Aabb bounds{{-2.3f, -1.1f, -1.1f}, {2.3f, 1.1f, 1.1f}};
  const eng::Image image = renderOrFail(bounds, instances);
  const glm::ivec4 left = pixel(image, 128 - 67, 128), middle = pixel(image, 128, 128), right = pixel(image, 128 + 67, 128);
  EXPECT_GT(left.r, left.b + 80) << "left is red";
  EXPECT_GT(right.b, right.r + 80) << "right is blue";
  EXPECT_LT(std::abs(middle.r - middle.b), 20) << "middle keeps its grey";
  // One record per material (and the default) per instance, every frame.
  const eng::vk::FrameStats stats = vk_test::renderer().lastFrameStats();
  EXPECT_EQ(stats.materials, 3u * 2u);
  EXPECT_EQ(stats.draws, 1u) << "still one instanced draw";
}

TEST(InstanceMaterialsValidity, TooManyOrNonFiniteRecordsAreRefused) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const std::vector<eng::vk::InstanceMaterial> two(2);
  const eng::vk::ModelInstance tooMany{&*gpu, glm::mat4(1.0f), weights, {}, two};
  auto refused = vk_test::renderer().render(viewOf(model.bounds()), {&tooMany, 1});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("instance 0 ("), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("2 materials given, the model has 1"), std::string::npos)
      << refused.error().message;
  eng::vk::InstanceMaterial nan;
  nan.baseColorFactor.g = std::numeric_limits<float>::quiet_NaN();
  const eng::vk::ModelInstance broken{&*gpu, glm::mat4(1.0f), weights, {}, {&nan, 1}};
  auto nanRefused = vk_test::renderer().render(viewOf(model.bounds()), {&broken, 1});
  ASSERT_FALSE(nanRefused);
  EXPECT_NE(nanRefused.error().message.find("material 0 has a non-finite value"), std::string::npos)
      << nanRefused.error().message;
}

}  // namespace
