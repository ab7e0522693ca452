// Loads every third-party file in ../shared/assets and checks the facts its
// own README (../shared/assets/README.md) states (skipped when ../shared is absent).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"

namespace {

using testing_support::sharedDir;

eng::Model load(const std::string& relative) {
  auto model = eng::loadModel(sharedDir() / "assets" / relative);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  return model.ok() ? std::move(*model) : eng::Model{};
}

const eng::Mesh* meshWithTargets(const eng::Model& model) {
  for (const eng::Mesh& mesh : model.meshes)
    if (!mesh.targetNames.empty()) return &mesh;
  return nullptr;
}

bool anyNonZero(const std::vector<glm::vec3>& deltas) {
  return std::any_of(deltas.begin(), deltas.end(), [](const glm::vec3& d) { return d != glm::vec3(0.0f); });
}

const eng::Animation* findAnimation(const eng::Model& model, const std::string& name) {
  for (const eng::Animation& a : model.animations)
    if (a.name == name) return &a;
  return nullptr;
}

TEST(SharedAssets, FacecapHas52ArkitTargetsOnTheHead) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("facecap.glb");
  ASSERT_GE(model.meshes.size(), 3u) << "head, eyes and teeth are separate meshes";
  const eng::Mesh* head = meshWithTargets(model);
  ASSERT_NE(head, nullptr);
  ASSERT_EQ(head->primitives.size(), 1u);
  EXPECT_EQ(head->primitives[0].vertexCount(), 2694u);
  ASSERT_EQ(head->targetNames.size(), 52u);
  for (const char* name : {"eyeBlink_L", "eyeBlink_R", "mouthSmile_L", "mouthSmile_R", "jawOpen", "browInnerUp"})
    EXPECT_NE(std::find(head->targetNames.begin(), head->targetNames.end(), name), head->targetNames.end()) << name;
  const auto blink = std::find(head->targetNames.begin(), head->targetNames.end(), "eyeBlink_L") - head->targetNames.begin();
  const eng::MorphTarget& target = head->primitives[0].targets[blink];
  EXPECT_TRUE(anyNonZero(target.positions));
  EXPECT_TRUE(anyNonZero(target.normals));
  EXPECT_TRUE(std::any_of(head->defaultWeights.begin(), head->defaultWeights.end(), [](float w) { return w != 0.0f; }));
  const bool quantizedScale = std::any_of(model.nodes.begin(), model.nodes.end(), [](const eng::Node& n) {
    return std::abs(n.scale.x - 0.00195f) < 0.00001f;
  });
  EXPECT_TRUE(quantizedScale) << "a node scales the quantized positions by 0.00195";
  EXPECT_EQ(model.meshes.size() - 1,
            static_cast<size_t>(std::count_if(model.meshes.begin(), model.meshes.end(),
                                              [](const eng::Mesh& m) { return m.targetNames.empty(); })));

  ASSERT_EQ(model.animations.size(), 4u);
  size_t weightsAnimations = 0;
  for (const eng::Animation& anim : model.animations) {
    if (anim.channels.empty()) continue;
    ++weightsAnimations;
    ASSERT_EQ(anim.channels.size(), 1u);
    const eng::WeightsChannel& ch = anim.channels[0];
    EXPECT_EQ(ch.targetCount, 52u);
    EXPECT_EQ(ch.interpolation, eng::Interpolation::Linear);
    EXPECT_EQ(ch.values.size(), ch.times.size() * 52);
    EXPECT_GT(anim.duration(), 1.0f);
  }
  EXPECT_EQ(weightsAnimations, 1u);
}

TEST(SharedAssets, RobotExpressiveHeadSharesThreeTargetsAcrossThreePrimitives) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("RobotExpressive.glb");
  const auto head = std::find_if(model.meshes.begin(), model.meshes.end(), [](const eng::Mesh& m) { return m.name == "Head"; });
  ASSERT_NE(head, model.meshes.end());
  ASSERT_EQ(head->primitives.size(), 3u);
  EXPECT_EQ(head->targetNames, (std::vector<std::string>{"Angry", "Surprised", "Sad"}));
  for (const eng::Primitive& prim : head->primitives) {
    ASSERT_EQ(prim.targets.size(), 3u);
    for (const eng::MorphTarget& t : prim.targets) EXPECT_EQ(t.positions.size(), prim.vertexCount());
  }
  // Only the face primitive moves; the other two carry all-zero deltas.
  for (int t = 0; t < 3; ++t) {
    EXPECT_FALSE(anyNonZero(head->primitives[0].targets[t].positions));
    EXPECT_TRUE(anyNonZero(head->primitives[2].targets[t].positions));
  }
  ASSERT_EQ(model.animations.size(), 14u);
  for (const eng::Animation& anim : model.animations) {
    EXPECT_EQ(anim.channels.size(), 1u) << anim.name;
    EXPECT_GT(anim.otherChannelCount, 0u) << anim.name << " also moves bones";
  }
  EXPECT_NE(findAnimation(model, "Dance"), nullptr);
  const eng::WeightLayout layout(model);
  std::vector<float> weights = layout.defaults();
  EXPECT_EQ(*layout.setByName(weights, "Surprised", 1.0f), 1);
}

TEST(SharedAssets, AnimatedMorphCubeMorphsPositionNormalAndTangent) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("khronos/AnimatedMorphCube/AnimatedMorphCube.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  const eng::Primitive& prim = model.meshes[0].primitives.at(0);
  EXPECT_EQ(prim.vertexCount(), 24u);
  ASSERT_EQ(prim.targets.size(), 2u);
  for (const eng::MorphTarget& t : prim.targets) {
    EXPECT_EQ(t.positions.size(), 24u);
    EXPECT_EQ(t.normals.size(), 24u);
    EXPECT_EQ(t.tangents.size(), 24u);
  }
  ASSERT_NE(findAnimation(model, "Square"), nullptr);
  EXPECT_EQ(findAnimation(model, "Square")->channels.size(), 1u);
}

TEST(SharedAssets, AnimatedMorphSphereHas1876VerticesAndGlobeAnimation) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("khronos/AnimatedMorphSphere/AnimatedMorphSphere.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.totalVertexCount(), 1876u);
  EXPECT_EQ(model.meshes[0].targetNames.size(), 2u);
  EXPECT_EQ(model.meshes[0].primitives[0].targets[1].tangents.size(), 1876u);
  ASSERT_NE(findAnimation(model, "Globe"), nullptr);
}

TEST(SharedAssets, MorphPrimitivesTestHasDefaultWeightHalfAndAJpegTexture) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("khronos/MorphPrimitivesTest/MorphPrimitivesTest.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  const eng::Mesh& mesh = model.meshes[0];
  ASSERT_EQ(mesh.primitives.size(), 2u);
  EXPECT_EQ(mesh.primitives[0].targets.size(), 1u);
  EXPECT_EQ(mesh.primitives[1].targets.size(), 1u);
  EXPECT_EQ(mesh.defaultWeights, std::vector<float>{0.5f});
  ASSERT_EQ(model.images.size(), 1u);
  EXPECT_GT(model.images[0].width, 0);
  EXPECT_EQ(model.images[0].rgba8.size(), static_cast<size_t>(model.images[0].width) * model.images[0].height * 4);
  ASSERT_FALSE(model.materials.empty());
  EXPECT_EQ(model.materials[0].baseColorImage, 0);
}

TEST(SharedAssets, MorphStressTestHasEightNamedTargetsAndThreeAnimations) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("khronos/MorphStressTest/MorphStressTest.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  const eng::Mesh& mesh = model.meshes[0];
  ASSERT_EQ(mesh.targetNames.size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(mesh.targetNames[k], "Key " + std::to_string(k + 1));
  const bool has1504 = std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                                   [](const eng::Primitive& p) { return p.vertexCount() == 1504; });
  EXPECT_TRUE(has1504);
  for (const eng::Primitive& p : mesh.primitives)
    for (const eng::MorphTarget& t : p.targets) {
      EXPECT_EQ(t.positions.size(), p.vertexCount());
      EXPECT_EQ(t.normals.size(), p.vertexCount());
    }
  for (const char* name : {"Individuals", "TheWave", "Pulse"}) {
    const eng::Animation* anim = findAnimation(model, name);
    ASSERT_NE(anim, nullptr) << name;
    ASSERT_EQ(anim->channels.size(), 1u);
    EXPECT_EQ(anim->channels[0].targetCount, 8u);
  }
  EXPECT_GE(model.images.size(), 2u) << "PNG textures decoded";
}

TEST(SharedAssets, SimpleMorphHasThreeVerticesTwoTargetsOneAnimation) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = load("khronos/SimpleMorph/SimpleMorph.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.totalVertexCount(), 3u);
  EXPECT_EQ(model.meshes[0].targetNames, (std::vector<std::string>{"target_0", "target_1"}));
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(model.animations[0].channels.size(), 1u);
}

// Every file loads without warnings but the one that names what is not drawn:
// MorphStressTest's ambient occlusion lies on a second UV set, and a primitive
// carries one.
TEST(SharedAssets, EveryFileLoadsWithoutWarnings) {
  FACIAL_REQUIRE_SHARED();
  const std::pair<const char*, const char*> files[] = {
      {"facecap.glb", nullptr},
      {"RobotExpressive.glb", nullptr},
      {"khronos/AnimatedMorphCube/AnimatedMorphCube.gltf", nullptr},
      {"khronos/AnimatedMorphSphere/AnimatedMorphSphere.gltf", nullptr},
      {"khronos/MorphPrimitivesTest/MorphPrimitivesTest.gltf", nullptr},
      {"khronos/MorphStressTest/MorphStressTest.gltf",
       "material 0: its occlusionTexture reads TEXCOORD_1, unlike its base colour (TEXCOORD_0); it is not drawn"},
      {"khronos/SimpleMorph/SimpleMorph.gltf", nullptr}};
  for (const auto& [file, expected] : files) {
    const eng::Model model = load(file);
    EXPECT_FALSE(model.meshes.empty()) << file;
    if (expected)
      EXPECT_EQ(model.warnings, std::vector<std::string>{expected}) << file;
    else
      EXPECT_TRUE(model.warnings.empty()) << file << ": " << (model.warnings.empty() ? "" : model.warnings.front());
    EXPECT_TRUE(model.bounds().valid()) << file;
  }
}

}  // namespace
