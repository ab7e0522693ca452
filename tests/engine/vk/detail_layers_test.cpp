// Material detail layers (texture cross-blending): each layer's image is
// blended over the base colour by (its target's current weight x strength),
// read in the fragment shader from the same active list as the morphing.
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/log.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

eng::Image solidImage(int w, int h, glm::u8vec4 colour) {
  eng::Image img;
  img.name = "solid";
  img.width = w;
  img.height = h;
  for (int i = 0; i < w * h; ++i) img.rgba8.insert(img.rgba8.end(), {colour.r, colour.g, colour.b, colour.a});
  return img;
}

// A grey sphere whose material has a red layer on t1 and a blue layer (other size) on t2.
eng::Model layeredSphere() {
  testing_support::SphereSpec spec;
  spec.color = {0.7f, 0.7f, 0.7f, 1.0f};
  eng::Model model = testing_support::makeSphereModel(spec);
  model.images.push_back(solidImage(4, 4, {255, 0, 0, 255}));
  model.images.push_back(solidImage(2, 8, {0, 0, 255, 255}));
  model.materials[0].detailLayers = {{0, testing_support::targetName(1), 1.0f}, {1, testing_support::targetName(2), 0.5f}};
  return model;
}

glm::ivec4 centreWith(const eng::vk::GpuModel& gpu, const eng::Model& model, std::vector<float> weights) {
  const eng::vk::ModelInstance instance{&gpu, glm::mat4(1.0f), weights};
  auto image = vk_test::renderer().render({eng::OrbitCamera::frame(model.bounds()), {}}, {&instance, 1});
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  return image ? vk_test::pixel(*image, 128, 128) : glm::ivec4(0);
}

TEST(DetailLayers, LayerFollowsItsTargetWeight) {
  const eng::Model model = layeredSphere();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const glm::ivec4 off = centreWith(*gpu, model, {0, 0, 0, 0});
  const glm::ivec4 half = centreWith(*gpu, model, {0, 0.5f, 0, 0});
  const glm::ivec4 full = centreWith(*gpu, model, {0, 1.0f, 0, 0});
  EXPECT_LT(std::abs(off.r - off.g), 15) << "grey base without the layer";
  EXPECT_GT(full.r, full.g + 80) << "red layer at weight 1";
  EXPECT_GT(half.r - half.g, 20);
  EXPECT_LT(half.r - half.g, full.r - full.g) << "weight 0.5 blends half way";
}

TEST(DetailLayers, StrengthScalesTheWeightAndLayersOfOtherSizesWork) {
  const eng::Model model = layeredSphere();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const glm::ivec4 blue = centreWith(*gpu, model, {0, 0, 1.0f, 0});  // strength 0.5: half blue
  EXPECT_GT(blue.b, blue.r + 20);
  const glm::ivec4 bothFull = centreWith(*gpu, model, {0, 1.0f, 1.0f, 0});
  EXPECT_GT(bothFull.b, 40) << "the blue layer (later) blends over the red one";
  EXPECT_GT(bothFull.r, 40);
}

// A modulating layer (the head's creases carried onto another face) scales
// the colour under it by twice its own: 0.5 (sRGB 188) leaves the grey as
// it is, 0 blackens it, and at weight 0.5 the scale is half way.
TEST(DetailLayers, ModulatingLayerScalesTheColourUnderIt) {
  eng::Model model = layeredSphere();
  model.images.push_back(solidImage(4, 4, {188, 188, 188, 255}));
  model.images.push_back(solidImage(4, 4, {0, 0, 0, 255}));
  model.materials[0].detailLayers = {{2, testing_support::targetName(1), 1.0f, eng::DetailBlend::Modulate},
                                     {3, testing_support::targetName(2), 1.0f, eng::DetailBlend::Modulate}};
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const glm::ivec4 off = centreWith(*gpu, model, {0, 0, 0, 0});
  const glm::ivec4 neutral = centreWith(*gpu, model, {0, 1.0f, 0, 0});
  const glm::ivec4 black = centreWith(*gpu, model, {0, 0, 1.0f, 0});
  const glm::ivec4 half = centreWith(*gpu, model, {0, 0, 0.5f, 0});
  EXPECT_LT(std::abs(neutral.g - off.g), 4) << "0.5 modulates by 1";
  EXPECT_LT(black.g, off.g / 6) << "0 modulates by 0";
  EXPECT_GT(half.g, black.g + 20);
  EXPECT_LT(half.g, off.g - 20) << "weight 0.5: half way (in linear light)";
  EXPECT_LT(std::abs(half.r - half.g), 15) << "a grey modulation keeps the grey";
}

// A mixing layer stands for the texture (painted over the same UVs): the
// material's factor and the vertex colours tint it as they tint the texture,
// so the head's creases and pallor, painted for its skin, stay dark on the
// head made dark by its factor (they drew pale stripes and an ashen face).
TEST(DetailLayers, MixingLayerIsTintedLikeTheTextureItStandsFor) {
  eng::Model model = layeredSphere();
  model.images.push_back(solidImage(4, 4, {160, 160, 160, 255}));  // a pale crease over a white texture
  model.materials[0].detailLayers = {{2, testing_support::targetName(1), 1.0f}};
  model.materials[0].baseColorFactor = {0.12f, 0.12f, 0.12f, 1.0f};  // a dark skin
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const glm::ivec4 off = centreWith(*gpu, model, {0, 0, 0, 0});
  const glm::ivec4 creased = centreWith(*gpu, model, {0, 1.0f, 0, 0});
  EXPECT_LT(creased.g, off.g - 10) << "the crease darkens the dark skin (" << creased.g << " against " << off.g << ")";

  model.materials[0].baseColorFactor = glm::vec4(1.0f);
  for (eng::Primitive& prim : model.meshes[0].primitives) prim.colors.assign(prim.vertexCount(), {0.12f, 0.12f, 0.12f, 1.0f});
  auto painted = vk_test::renderer().upload(model);
  ASSERT_TRUE(painted) << painted.error().message;
  const glm::ivec4 paintedOff = centreWith(*painted, model, {0, 0, 0, 0});
  const glm::ivec4 paintedCreased = centreWith(*painted, model, {0, 1.0f, 0, 0});
  EXPECT_LT(std::abs(paintedOff.g - off.g), 4) << "vertex colours tint as the factor does";
  EXPECT_LT(std::abs(paintedCreased.g - creased.g), 4);
}

// Uploads `model`, the warnings logged meanwhile kept in `warnings`.
auto uploadKeepingWarnings(const eng::Model& model, std::vector<std::string>& warnings) {
  const eng::LogSink previous = eng::setLogSink([&](eng::LogLevel level, std::string_view m) {
    if (level == eng::LogLevel::Warning) warnings.emplace_back(m);
  });
  auto gpu = vk_test::renderer().upload(model);
  eng::setLogSink(previous);
  return gpu;
}

TEST(DetailLayers, LayerOnAMissingTargetStaysHidden) {
  eng::Model model = layeredSphere();
  model.materials[0].detailLayers = {{0, "noSuchTarget", 1.0f}};
  std::vector<std::string> warnings;
  auto gpu = uploadKeepingWarnings(model, warnings);
  ASSERT_TRUE(gpu) << gpu.error().message;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("noSuchTarget"), std::string::npos) << warnings[0];
  const glm::ivec4 c = centreWith(*gpu, model, {1, 1, 1, 1});
  EXPECT_LT(std::abs(c.r - c.g), 15);
}

// A face stripped of its targets misses every layer's: one line names them all.
TEST(DetailLayers, LayersOnMissingTargetsAreOneWarning) {
  eng::Model model = layeredSphere();
  model.materials[0].detailLayers = {{0, "browsUp", 1.0f}, {1, "noseWrinkle", 1.0f}, {0, testing_support::targetName(1), 1.0f}};
  std::vector<std::string> warnings;
  auto gpu = uploadKeepingWarnings(model, warnings);
  ASSERT_TRUE(gpu) << gpu.error().message;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("detail layer targets 'browsUp', 'noseWrinkle' are not morph targets of this mesh (2 of 3)"),
            std::string::npos)
      << warnings[0];
}

TEST(DetailLayersValidity, LayerImageOutOfRangeIsAnError) {
  eng::Model model = layeredSphere();
  model.sourcePath = "layers.glb";
  model.materials[0].detailLayers[1].image = 7;
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_FALSE(gpu);
  EXPECT_NE(gpu.error().message.find("layers.glb: material 0 'sphere material' detail layer 1 't2' uses image 7 of 2 images"),
            std::string::npos)
      << gpu.error().message;
}

}  // namespace
