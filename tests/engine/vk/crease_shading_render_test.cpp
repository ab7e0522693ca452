// Crease darkening on the GPU: the vertex shader sums each active target's
// baked darkening (engine/scene/crease_shading.h) like its deltas, so skin
// that a target bunches up shades darker, in proportion to the weight.
#include <vector>

#include <gtest/gtest.h>

#include "tests/common/test_meshes.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

// A flat grey sheet facing +Z whose one target squeezes it to half its width:
// flat before and after, so the lights see the same surface and only the
// crease darkening can change its shade.
eng::Model squeezableSheet() {
  eng::Model model;
  eng::Primitive p = testing_support::flatSheet(21);
  eng::MorphTarget squeeze;
  for (const glm::vec3& q : p.positions) squeeze.positions.push_back({-0.5f * q.x, 0, 0});
  p.targets.push_back(squeeze);
  p.material = 0;
  eng::Material grey;
  grey.baseColorFactor = {0.15f, 0.15f, 0.15f, 1.0f};  // dark enough that the tone curve stays steep
  model.materials.push_back(grey);
  eng::Mesh mesh;
  mesh.name = "sheet";
  mesh.targetNames = {"squeeze"};
  mesh.defaultWeights = {0.0f};
  mesh.primitives.push_back(std::move(p));
  model.meshes.push_back(std::move(mesh));
  eng::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  model.roots.push_back(0);
  return model;
}

int centreBrightness(const eng::vk::GpuModel& gpu, const eng::Model& model, float weight) {
  const std::vector<float> weights{weight};
  const eng::vk::ModelInstance instance{&gpu, glm::mat4(1.0f), weights};
  auto image = vk_test::renderer().render({eng::OrbitCamera::frame(model.bounds()), {}}, {&instance, 1});
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  if (!image) return 0;
  const glm::ivec4 c = vk_test::pixel(*image, 128, 128);
  return c.r + c.g + c.b;
}

TEST(CreaseShadingRender, BunchedSkinShadesDarkerWithTheWeight) {
  const eng::Model model = squeezableSheet();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const int rest = centreBrightness(*gpu, model, 0.0f);
  const int half = centreBrightness(*gpu, model, 0.5f);
  const int full = centreBrightness(*gpu, model, 1.0f);
  EXPECT_GT(rest, 150) << "the sheet is lit";
  EXPECT_LT(rest, 600) << "and not clipped, so darkening shows";
  EXPECT_LT(full, rest - 40) << "squeezed to half its width, the skin folds and darkens";
  EXPECT_LT(half, rest - 10);
  EXPECT_GT(half, full + 10) << "darkening follows the weight";
}

}  // namespace
