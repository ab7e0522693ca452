// The checked-in data/head.glb: loads, carries every action-unit target and
// the detail layers, and matches what `facial make-head` generates now (run
// `facial make-head --out data/head.glb` after changing the generator).
#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"
#include "tests/bake/head/built_in_head.h"

namespace {

const eng::Model& checkedIn() {
  static const eng::Model model = [] {
    auto loaded = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded).value();
  }();
  return model;
}

TEST(HeadAsset, LoadsWithEveryActionUnitTarget) {
  const eng::Mesh& mesh = head_testing::headMesh(checkedIn());
  std::vector<std::string> expected;
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) expected.emplace_back(info.name);
  EXPECT_EQ(mesh.targetNames, expected);
  EXPECT_TRUE(checkedIn().warnings.empty());
}

TEST(HeadAsset, MatchesRegeneration) {
  const eng::Model& file = checkedIn();
  const eng::Model& fresh = head_testing::builtInHead().model;
  ASSERT_EQ(file.meshes.size(), fresh.meshes.size());
  for (size_t m = 0; m < fresh.meshes.size(); ++m) {
    EXPECT_EQ(file.meshes[m].name, fresh.meshes[m].name);
    ASSERT_EQ(file.meshes[m].primitives.size(), fresh.meshes[m].primitives.size()) << fresh.meshes[m].name;
    for (size_t p = 0; p < fresh.meshes[m].primitives.size(); ++p) {
      const eng::Primitive &a = file.meshes[m].primitives[p], &b = fresh.meshes[m].primitives[p];
      ASSERT_EQ(a.vertexCount(), b.vertexCount()) << "regenerate data/head.glb with facial make-head";
      ASSERT_EQ(a.indices, b.indices) << "regenerate data/head.glb with facial make-head";
      float worst = 0.0f;
      for (size_t v = 0; v < a.vertexCount(); ++v) worst = std::max(worst, glm::length(a.positions[v] - b.positions[v]));
      for (size_t t = 0; t < b.targets.size(); ++t)
        for (size_t v = 0; v < a.vertexCount(); ++v)
          worst = std::max(worst, glm::length(a.targets[t].positions[v] - b.targets[t].positions[v]));
      EXPECT_LT(worst, 1e-5f) << fresh.meshes[m].name << " primitive " << p
                              << " differs from regeneration: run facial make-head --out data/head.glb";
    }
  }
}

TEST(HeadAsset, KeepsMaterialsImagesAndDetailLayers) {
  const eng::Model& file = checkedIn();
  const eng::Model& fresh = head_testing::builtInHead().model;
  ASSERT_EQ(file.materials.size(), fresh.materials.size());
  ASSERT_EQ(file.images.size(), fresh.images.size());
  for (size_t i = 0; i < fresh.images.size(); ++i) {
    EXPECT_EQ(file.images[i].width, fresh.images[i].width);
    EXPECT_EQ(file.images[i].rgba8, fresh.images[i].rgba8) << fresh.images[i].name;
  }
  const eng::Material& skin = file.materials[0];
  ASSERT_EQ(skin.detailLayers.size(), fresh.materials[0].detailLayers.size());
  for (size_t l = 0; l < skin.detailLayers.size(); ++l) {
    EXPECT_EQ(skin.detailLayers[l].target, fresh.materials[0].detailLayers[l].target);
    EXPECT_EQ(skin.detailLayers[l].image, fresh.materials[0].detailLayers[l].image);
    EXPECT_FLOAT_EQ(skin.detailLayers[l].strength, fresh.materials[0].detailLayers[l].strength);
  }
}

}  // namespace
