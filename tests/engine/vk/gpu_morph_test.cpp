// The vertex shader's morphing and skinning agree with the CPU reference
// (eng::posePrimitiveCpu: eng::morphPrimitiveCpu, then eng::skinPrimitiveCpu):
// max position error <= 1e-5 x the primitive's bounding-box diagonal, on
// procedural meshes (incl. 256 targets all active, several instances with
// independent weights and poses) and on every shared asset (skinned ones in
// the rest pose and in an animation pose).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/skinning.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

constexpr float kRelativePositionTolerance = 1e-5f;
constexpr float kNormalTolerance = 1e-4f;

// Deterministic weights in [-0.4, 1.2], every one non-zero.
std::vector<float> variedWeights(size_t count, float phase) {
  std::vector<float> w(count);
  for (size_t i = 0; i < count; ++i) w[i] = 0.4f + 0.8f * std::sin(1.7f * float(i) + phase);
  for (float& x : w) {
    if (std::abs(x) < 0.01f) x = 0.05f;
  }
  return w;
}

struct Agreement {
  float maxPositionError = 0.0f;
  float diagonal = 0.0f;
  float maxNormalError = 0.0f;
  float maxTangentError = 0.0f;
  size_t comparedPrimitives = 0;
  size_t skinnedPrimitives = 0;
};

// Captures every (instance, mesh, primitive) on the GPU and compares with the
// CPU. instanceWorld: each instance's pose as node world matrices (none: rest pose).
Agreement compareWithCpu(const eng::Model& model, const eng::vk::GpuModel& gpu,
                         const std::vector<std::vector<float>>& instanceWeights,
                         const std::vector<std::vector<glm::mat4>>& instanceWorld = {}) {
  std::vector<eng::vk::ModelInstance> instances;
  for (size_t i = 0; i < instanceWeights.size(); ++i)
    instances.push_back({&gpu, glm::mat4(1.0f), instanceWeights[i],
                         i < instanceWorld.size() ? std::span<const glm::mat4>(instanceWorld[i])
                                                  : std::span<const glm::mat4>()});
  auto captured = vk_test::renderer().capture(instances);
  EXPECT_TRUE(captured) << (captured ? "" : captured.error().message);
  if (!captured) return {};
  const eng::WeightLayout layout(model);
  Agreement a;
  for (const eng::vk::CapturedPrimitive& c : *captured) {
    const eng::Primitive& prim = model.meshes[size_t(c.mesh)].primitives[size_t(c.primitive)];
    const std::span<const float> meshWeights = *layout.meshWeights(instanceWeights[c.instance], c.mesh);
    std::vector<glm::vec3> positions(prim.vertexCount()), normals(prim.vertexCount());
    // The capture skins with the first scene node drawing the mesh.
    const auto nodes = gpu.meshNodes();
    const auto node = std::find_if(nodes.begin(), nodes.end(), [&](const eng::MeshNode& n) { return n.mesh == c.mesh; });
    const int meshNode = node == nodes.end() ? -1 : node->node;
    const std::span<const glm::mat4> world =
        c.instance < instanceWorld.size() ? std::span<const glm::mat4>(instanceWorld[c.instance]) : gpu.restWorld();
    eng::posePrimitiveCpu(model, meshNode, prim, meshWeights, world, positions, normals);
    const bool skinned = meshNode >= 0 && model.nodes[meshNode].skin >= 0 && prim.influenceSets() > 0;
    if (skinned) ++a.skinnedPrimitives;
    eng::Aabb box;
    for (const glm::vec3& p : prim.positions) box.extend(p);
    for (const glm::vec3& p : positions) box.extend(p);
    a.diagonal = box.diagonal();
    float worst = 0.0f;
    for (size_t v = 0; v < positions.size(); ++v) {
      worst = std::max(worst, glm::length(c.positions[v] - positions[v]));
      if (glm::dot(normals[v], normals[v]) > 0.5f)  // skip normals blended to nothing
        a.maxNormalError = std::max(a.maxNormalError, glm::length(c.normals[v] - normals[v]));
    }
    // Tangents: same lerp as normals, on tangent.xyz, renormalised (unskinned primitives).
    if (!prim.tangents.empty() && !skinned) {
      for (size_t v = 0; v < positions.size(); ++v) {
        glm::vec3 t = glm::vec3(prim.tangents[v]);
        for (size_t k = 0; k < prim.targets.size(); ++k)
          if (!prim.targets[k].tangents.empty()) t += meshWeights[k] * prim.targets[k].tangents[v];
        a.maxTangentError = std::max(a.maxTangentError, glm::length(glm::vec3(c.tangents[v]) - glm::normalize(t)));
        EXPECT_EQ(c.tangents[v].w, prim.tangents[v].w);
      }
    }
    EXPECT_LE(worst, kRelativePositionTolerance * a.diagonal)
        << model.sourcePath << " instance " << c.instance << " mesh " << c.mesh << " primitive " << c.primitive;
    a.maxPositionError = std::max(a.maxPositionError, worst / std::max(a.diagonal, 1e-30f));
    ++a.comparedPrimitives;
  }
  return a;
}

TEST(GpuMorph, CaptureIsSupportedOnTheTestDevice) {
  ASSERT_TRUE(vk_test::context().deviceInfo().vertexPipelineStores)
      << "the morph capture needs vertexPipelineStoresAndAtomics";
  EXPECT_TRUE(vk_test::renderer().canCapture());
}

TEST(GpuMorph, AgreesWithCpuOnASmallMesh) {
  testing_support::SphereSpec spec;
  spec.targets = 6;
  spec.tangents = true;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Agreement a = compareWithCpu(model, *gpu, {variedWeights(6, 0.0f)});
  EXPECT_EQ(a.comparedPrimitives, 1u);
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
  EXPECT_LE(a.maxTangentError, kNormalTolerance);
}

TEST(GpuMorph, RestPoseWhenAllWeightsAreZero) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> zeros(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), zeros};
  auto captured = vk_test::renderer().capture({&instance, 1});
  ASSERT_TRUE(captured) << captured.error().message;
  ASSERT_EQ(captured->size(), 1u);
  const eng::Primitive& prim = model.meshes[0].primitives[0];
  for (size_t v = 0; v < prim.vertexCount(); ++v) ASSERT_EQ((*captured)[0].positions[v], prim.positions[v]) << v;
  EXPECT_EQ(vk_test::renderer().lastFrameStats().activeWeights, 0u);
}

TEST(GpuMorph, TwoHundredFiftySixTargetsAllActive) {
  testing_support::SphereSpec spec;
  spec.rings = 12;
  spec.segments = 16;
  spec.targets = 256;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights = variedWeights(256, 0.3f);
  const Agreement a = compareWithCpu(model, *gpu, {weights});
  EXPECT_EQ(vk_test::renderer().lastFrameStats().activeWeights, 256u)
      << "more active targets than any small fixed cap";
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
}

TEST(GpuMorph, InstancesKeepIndependentWeights) {
  testing_support::SphereSpec spec;
  spec.targets = 40;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  std::vector<std::vector<float>> weights{variedWeights(40, 0.0f), std::vector<float>(40, 0.0f),
                                          variedWeights(40, 2.0f), variedWeights(40, 4.0f)};
  weights[1][7] = 1.0f;  // one active target only
  const Agreement a = compareWithCpu(model, *gpu, weights);
  EXPECT_EQ(a.comparedPrimitives, 4u);
  EXPECT_EQ(vk_test::renderer().lastFrameStats().activeWeights, 40u + 1u + 40u + 40u);
}

TEST(GpuMorph, MeshWithoutNormalDeltasKeepsRestNormals) {
  testing_support::SphereSpec spec;
  spec.normalDeltas = false;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Agreement a = compareWithCpu(model, *gpu, {variedWeights(4, 1.0f)});
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
}

TEST(GpuMorph, AgreesWithCpuOnEverySharedAsset) {
  FACIAL_REQUIRE_SHARED();
  vk_test::forEachSharedModel([](const std::filesystem::path& file, const eng::Model& model,
                                 const eng::vk::GpuModel& gpu) {
    const size_t count = gpu.weightCount();
    const Agreement a = compareWithCpu(model, gpu, {variedWeights(count, 0.0f), variedWeights(count, 1.3f)});
    EXPECT_GT(a.comparedPrimitives, 0u);
    EXPECT_LE(a.maxNormalError, kNormalTolerance);
    std::printf("  %s: %zu primitives x 2 instances, max position error %.2e x diagonal, normal error %.2e\n",
                file.filename().string().c_str(), a.comparedPrimitives / 2, a.maxPositionError, a.maxNormalError);
    if (model.animations.empty() || model.skins.empty()) return;
    // Skinned: every animation's pose half way through, two instances in different poses.
    for (const eng::Animation& anim : model.animations) {
      if (anim.nodeChannels.empty()) continue;
      std::vector<std::vector<glm::mat4>> world(2);
      for (size_t i = 0; i < 2; ++i) {
        eng::Pose pose = eng::restPose(model);
        eng::sampleAnimation(anim, anim.duration() * (0.3f + 0.4f * float(i)), pose);
        eng::poseWorldMatrices(model, pose, world[i]);
      }
      const Agreement posed = compareWithCpu(model, gpu, {variedWeights(count, 0.5f), variedWeights(count, 2.0f)}, world);
      EXPECT_GT(posed.skinnedPrimitives, 0u);
      EXPECT_LE(posed.maxNormalError, kNormalTolerance) << anim.name;
    }
  });
}

// A strip of 2 x 16 quads bent by a chain of three joints, two influence
// groups per vertex (8 influences, the second group carrying a share).
eng::Model makeSkinnedStrip() {
  eng::Model model;
  eng::Mesh mesh;
  eng::Primitive prim;
  constexpr int kColumns = 17;
  for (int x = 0; x < kColumns; ++x)
    for (int y = 0; y < 2; ++y) {
      prim.positions.push_back({float(x) / 8.0f, float(y) * 0.2f, 0.0f});
      prim.normals.push_back({0.0f, 0.0f, 1.0f});
      const float t = float(x) / float(kColumns - 1) * 2.0f;  // 0..2 along the chain
      const float w1 = std::clamp(1.0f - std::abs(t - 1.0f), 0.0f, 1.0f);
      const float w0 = std::max(0.0f, 1.0f - t), w2 = std::max(0.0f, t - 1.0f);
      prim.joints.push_back({0, 1, 2, 0});
      prim.jointWeights.push_back(glm::vec4(w0, w1, w2, 0.0f) * 0.75f);
      prim.joints.push_back({2, 1, 0, 1});
      prim.jointWeights.push_back(glm::vec4(w2, w1, w0, 0.0f) * 0.25f);
    }
  for (uint32_t x = 0; x + 1 < kColumns; ++x) {
    const uint32_t a = 2 * x, b = a + 1, c = a + 2, d = a + 3;
    prim.indices.insert(prim.indices.end(), {a, c, d, a, d, b});
  }
  eng::MorphTarget bulge;
  for (const glm::vec3& p : prim.positions) bulge.positions.push_back({0.0f, 0.0f, 0.3f * std::sin(8.0f * p.x)});
  bulge.normals.assign(prim.positions.size(), glm::vec3(0.1f, 0.0f, 0.0f));
  prim.targets.push_back(bulge);
  mesh.primitives.push_back(prim);
  mesh.targetNames = {"bulge"};
  mesh.defaultWeights = {0.0f};
  model.meshes.push_back(mesh);
  // Node 0 draws the mesh, moved away: the joint matrices must undo its transform.
  model.nodes.resize(4);
  model.nodes[0].mesh = 0;
  model.nodes[0].skin = 0;
  model.nodes[0].translation = {5.0f, -2.0f, 1.0f};
  model.nodes[1].children = {2};
  model.nodes[2].parent = 1;
  model.nodes[2].translation = {1.0f, 0.0f, 0.0f};
  model.nodes[2].children = {3};
  model.nodes[3].parent = 2;
  model.nodes[3].translation = {1.0f, 0.0f, 0.0f};
  model.roots = {0, 1};
  eng::Skin skin;
  skin.joints = {1, 2, 3};
  for (int j = 0; j < 3; ++j) skin.inverseBindMatrices.push_back(glm::translate(glm::mat4(1.0f), {-float(j), 0.0f, 0.0f}));
  model.skins.push_back(skin);
  return model;
}

std::vector<glm::mat4> bentPose(const eng::Model& model, float degrees) {
  eng::Pose pose = eng::restPose(model);
  pose.rotations[2] = glm::angleAxis(glm::radians(degrees), glm::vec3(0, 0, 1));
  pose.rotations[3] = glm::angleAxis(glm::radians(-0.5f * degrees), glm::vec3(0, 1, 0));
  pose.scales[3] = glm::vec3(1.2f);
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, pose, world);
  return world;
}

TEST(GpuSkin, AgreesWithCpuOnABentStripWithEightInfluences) {
  const eng::Model model = makeSkinnedStrip();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Agreement a = compareWithCpu(model, *gpu, {{0.0f}, {0.8f}, {1.0f}},
                                     {bentPose(model, 0.0f), bentPose(model, 40.0f), bentPose(model, -75.0f)});
  EXPECT_EQ(a.comparedPrimitives, 3u);
  EXPECT_EQ(a.skinnedPrimitives, 3u);
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
  EXPECT_EQ(vk_test::renderer().lastFrameStats().jointMatrices, 9u) << "three joints per instance";
}

TEST(GpuSkin, BentPoseActuallyMovesVertices) {
  // Guards the agreement test against a capture that ignores the pose.
  const eng::Model model = makeSkinnedStrip();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights{0.0f};
  const std::vector<glm::mat4> world = bentPose(model, 60.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights, world};
  auto captured = vk_test::renderer().capture({&instance, 1});
  ASSERT_TRUE(captured) << captured.error().message;
  const eng::Primitive& prim = model.meshes[0].primitives[0];
  // Mesh node space: the rest pose puts vertex 0 at (0,0,0) - (5,-2,1) (the node's offset undone).
  EXPECT_NEAR(glm::length((*captured)[0].positions[0] - glm::vec3(-5.0f, 2.0f, -1.0f)), 0.0f, 1e-4f);
  EXPECT_GT(glm::length((*captured)[0].positions.back() - (prim.positions.back() - glm::vec3(5.0f, -2.0f, 1.0f))), 0.5f);
}

// A character split into parts: mesh nodes that share one skin and one
// place (Ready Player Me's body, head, teeth, eyes, hair and outfit) get one
// set of joint matrices per instance, not one per part; a part placed
// elsewhere needs its own (the matrices undo the part's transform).
TEST(GpuSkin, PartsSharingASkinAndAPlaceShareTheirJointMatrices) {
  eng::Model model = makeSkinnedStrip();
  model.nodes.push_back(model.nodes[0]);  // node 4: a second part, same skin, same place
  model.roots.push_back(4);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights{0.0f};
  const std::vector<glm::mat4> world = bentPose(model, 30.0f);
  const std::array<eng::vk::ModelInstance, 2> instances{eng::vk::ModelInstance{&*gpu, glm::mat4(1.0f), weights, world},
                                                        eng::vk::ModelInstance{&*gpu, glm::mat4(1.0f), weights, world}};
  auto image = vk_test::renderer().render({eng::OrbitCamera::frame(model.bounds()), {}}, instances);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(vk_test::renderer().lastFrameStats().draws, 2u) << "one draw per part";
  EXPECT_EQ(vk_test::renderer().lastFrameStats().jointMatrices, 6u) << "three joints per instance, shared by both parts";

  model.nodes[4].translation += glm::vec3(0.0f, 1.0f, 0.0f);
  auto moved = vk_test::renderer().upload(model);
  ASSERT_TRUE(moved) << moved.error().message;
  const std::vector<glm::mat4> movedWorld = bentPose(model, 30.0f);
  const eng::vk::ModelInstance apart{&*moved, glm::mat4(1.0f), weights, movedWorld};
  auto second = vk_test::renderer().render({eng::OrbitCamera::frame(model.bounds()), {}}, {&apart, 1});
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(vk_test::renderer().lastFrameStats().jointMatrices, 6u) << "a part placed elsewhere has its own three";
}

TEST(GpuSkin, PoseOfTheWrongSizeIsRefused) {
  const eng::Model model = makeSkinnedStrip();
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights{0.0f};
  const std::vector<glm::mat4> world(2, glm::mat4(1.0f));
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights, world};
  auto captured = vk_test::renderer().capture({&instance, 1});
  ASSERT_FALSE(captured);
  EXPECT_NE(captured.error().message.find("pose of 2 nodes given, the model has 4"), std::string::npos)
      << captured.error().message;
}

}  // namespace
