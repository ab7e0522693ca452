// Golden-image tests: faces at several weight sets, every Khronos sample, and
// skinned models in their bind pose and in an animation pose, rendered
// 256x256 on the test device and compared with tests/goldens/*.png.
//
// Regenerate (after a deliberate change of the look; look at every image):
//   FACIAL_UPDATE_GOLDENS=1 build/bin/test_vk --gtest_filter='*Golden*'
//
// Tolerance (testing_support::ImageTolerance): a pixel differs when a channel
// is off by more than 16/255; at most 0.5% of the pixels may differ. That
// absorbs llvmpipe/GPU rasterisation and filtering differences along edges
// while any change of shape, expression, lighting or framing fails.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "importers/face_dressing.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/weights.h"
#include "engine/view/framing_bounds.h"
#include "tests/common/golden.h"
#include "tests/common/test_support.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

struct GoldenCase {
  std::string golden;  // tests/goldens/<golden>.png
  std::string file;    // under ../shared/assets
  std::vector<std::pair<std::string, float>> weights;  // over the model's defaults
  float yaw = 0.0f;
  float pitch = 0.0f;
  std::string clip;      // skeletal animation to pose by ("all": every one), empty = bind pose
  float clipTime = 0.0f;
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.golden; }

class GoldenAsset : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenAsset, MatchesGolden) {
  FACIAL_REQUIRE_SHARED();
  const GoldenCase& c = GetParam();
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / c.file);
  ASSERT_TRUE(model) << model.error().message;
  const eng::WeightLayout layout(*model);
  std::vector<float> weights = layout.defaults();
  for (const auto& [name, value] : c.weights) ASSERT_GT(*layout.setByName(weights, name, value), 0) << name;
  // Drawn as the programs draw a face: dressed when untextured (facecap).
  const std::optional<eng::Model> dressed = importers::dressedForDisplay(*model);
  auto gpu = vk_test::renderer().upload(dressed ? *dressed : *model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  eng::Pose pose = eng::restPose(*model);
  for (const eng::Animation& anim : model->animations)
    if (c.clip == "all" || anim.name == c.clip) eng::sampleAnimation(anim, c.clipTime, pose);
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(*model, pose, world);
  eng::vk::SceneView view;
  // Skinned models are framed as posed (their raw vertices are not where they are drawn).
  view.camera = eng::OrbitCamera::frame(model->skins.empty() ? eng::framingBounds(*model)
                                                                  : eng::posedBounds(*model, pose, weights));
  view.camera.yawDegrees = c.yaw;
  view.camera.pitchDegrees = c.pitch;
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights, world};
  auto image = vk_test::renderer().render(view, {&instance, 1});
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(testing_support::matchesGolden(*image, c.golden));
}

INSTANTIATE_TEST_SUITE_P(
    Faces, GoldenAsset,
    ::testing::Values(
        GoldenCase{"facecap_neutral", "facecap.glb", {}},
        GoldenCase{"facecap_smile", "facecap.glb", {{"mouthSmile_L", 1.0f}, {"mouthSmile_R", 1.0f}}},
        GoldenCase{"facecap_jaw_open", "facecap.glb", {{"jawOpen", 1.0f}}},
        GoldenCase{"facecap_blink", "facecap.glb", {{"eyeBlink_L", 1.0f}, {"eyeBlink_R", 1.0f}}},
        GoldenCase{"facecap_three_quarter_smile", "facecap.glb",
                   {{"mouthSmile_L", 0.8f}, {"mouthSmile_R", 0.8f}, {"cheekSquint_L", 0.5f}, {"cheekSquint_R", 0.5f}},
                   35.0f, 8.0f},
        GoldenCase{"robot_expressive_surprised", "RobotExpressive.glb", {{"Surprised", 1.0f}}}),
    [](const auto& info) { return info.param.golden; });

INSTANTIATE_TEST_SUITE_P(
    Khronos, GoldenAsset,
    ::testing::Values(
        GoldenCase{"animated_morph_cube", "khronos/AnimatedMorphCube/AnimatedMorphCube.gltf", {{"target_0", 0.6f}}, 30.0f,
                   20.0f},
        GoldenCase{"animated_morph_sphere", "khronos/AnimatedMorphSphere/AnimatedMorphSphere.gltf", {{"target_1", 0.7f}},
                   0.0f, 10.0f},
        GoldenCase{"morph_primitives_test", "khronos/MorphPrimitivesTest/MorphPrimitivesTest.gltf", {}, 0.0f, 50.0f},
        GoldenCase{"morph_stress_test", "khronos/MorphStressTest/MorphStressTest.gltf",
                   {{"Key 1", 1.0f}, {"Key 3", 0.5f}, {"Key 6", 1.0f}}, 0.0f, 25.0f},
        GoldenCase{"simple_morph", "khronos/SimpleMorph/SimpleMorph.gltf", {}}),
    [](const auto& info) { return info.param.golden; });

// Skinning: CesiumMan splits its walk into one clip per joint, so "all" plays the walk.
INSTANTIATE_TEST_SUITE_P(
    Skinned, GoldenAsset,
    ::testing::Values(
        GoldenCase{"cesium_man_bind_pose", "khronos/CesiumMan/glTF-Binary/CesiumMan.glb", {}, -90.0f, 0.0f},
        GoldenCase{"cesium_man_walk", "khronos/CesiumMan/glTF-Binary/CesiumMan.glb", {}, -60.0f, 5.0f, "all", 0.5f},
        GoldenCase{"robot_expressive_wave", "RobotExpressive.glb", {{"Surprised", 0.6f}}, 20.0f, 5.0f, "Wave", 0.9f}),
    [](const auto& info) { return info.param.golden; });

// Needs no shared assets: instancing, morphing and detail layers together.
TEST(GoldenProcedural, SphereInstancesWithDetailLayer) {
  testing_support::SphereSpec spec;
  spec.targets = 3;
  spec.tangents = true;
  eng::Model model = testing_support::makeSphereModel(spec);
  eng::Image stripes;
  stripes.name = "stripes";
  stripes.width = stripes.height = 16;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) stripes.rgba8.insert(stripes.rgba8.end(), {40, 90, 200, uint8_t(x < 8 ? 255 : 0)});
  model.images.push_back(stripes);
  model.materials[0].detailLayers = {{0, testing_support::targetName(2), 1.0f}};
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> rest{0, 0, 0}, bulge{1, 0, 0}, layered{0, 0.8f, 1.0f};
  const std::vector<eng::vk::ModelInstance> instances{
      {&*gpu, glm::translate(glm::mat4(1.0f), {-2.4f, 0, 0}), rest},
      {&*gpu, glm::mat4(1.0f), bulge},
      {&*gpu, glm::translate(glm::mat4(1.0f), {2.4f, 0, 0}), layered},
  };
  const eng::vk::SceneView view{eng::OrbitCamera::frame({{-3.5f, -1.3f, -1.3f}, {3.5f, 1.3f, 1.3f}}), {}};
  auto image = vk_test::renderer().render(view, instances);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(testing_support::matchesGolden(*image, "procedural_sphere_instances"));
}

}  // namespace
