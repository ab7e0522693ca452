// The vertex shader's morphing agrees with the CPU reference
// (eng::morphPrimitiveCpu): max position error <= 1e-5 x the primitive's
// bounding-box diagonal, on procedural meshes (incl. 256 targets all active,
// several instances with independent weights) and on every shared asset.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"
#include "tests/vk/test_models.h"
#include "tests/vk/vk_test_context.h"

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
};

// Captures every (instance, mesh, primitive) on the GPU and compares with the CPU.
Agreement compareWithCpu(const eng::Model& model, const eng::vk::GpuModel& gpu,
                         const std::vector<std::vector<float>>& instanceWeights) {
  std::vector<eng::vk::ModelInstance> instances;
  for (const auto& w : instanceWeights) instances.push_back({&gpu, glm::mat4(1.0f), w});
  auto captured = vk_test::renderer().capture(instances);
  EXPECT_TRUE(captured) << (captured ? "" : captured.error().message);
  if (!captured) return {};
  const eng::WeightLayout layout(model);
  Agreement a;
  for (const eng::vk::CapturedPrimitive& c : *captured) {
    const eng::Primitive& prim = model.meshes[size_t(c.mesh)].primitives[size_t(c.primitive)];
    const std::span<const float> meshWeights = layout.meshWeights(instanceWeights[c.instance], c.mesh);
    std::vector<glm::vec3> positions(prim.vertexCount()), normals(prim.vertexCount());
    eng::morphPrimitiveCpu(prim, meshWeights, positions, normals);
    eng::Aabb box;
    for (const glm::vec3& p : prim.positions) box.extend(p);
    a.diagonal = box.diagonal();
    float worst = 0.0f;
    for (size_t v = 0; v < positions.size(); ++v) {
      worst = std::max(worst, glm::length(c.positions[v] - positions[v]));
      if (glm::dot(normals[v], normals[v]) > 0.5f)  // skip normals blended to nothing
        a.maxNormalError = std::max(a.maxNormalError, glm::length(c.normals[v] - normals[v]));
    }
    // Tangents: same lerp as normals, on tangent.xyz, renormalised.
    if (!prim.tangents.empty()) {
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
  vk_test::SphereSpec spec;
  spec.targets = 6;
  spec.tangents = true;
  const eng::Model model = vk_test::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Agreement a = compareWithCpu(model, *gpu, {variedWeights(6, 0.0f)});
  EXPECT_EQ(a.comparedPrimitives, 1u);
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
  EXPECT_LE(a.maxTangentError, kNormalTolerance);
}

TEST(GpuMorph, RestPoseWhenAllWeightsAreZero) {
  const eng::Model model = vk_test::makeSphereModel({});
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
  vk_test::SphereSpec spec;
  spec.rings = 12;
  spec.segments = 16;
  spec.targets = 256;
  const eng::Model model = vk_test::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights = variedWeights(256, 0.3f);
  const Agreement a = compareWithCpu(model, *gpu, {weights});
  EXPECT_EQ(vk_test::renderer().lastFrameStats().activeWeights, 256u)
      << "more active targets than any small fixed cap";
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
}

TEST(GpuMorph, InstancesKeepIndependentWeights) {
  vk_test::SphereSpec spec;
  spec.targets = 40;
  const eng::Model model = vk_test::makeSphereModel(spec);
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
  vk_test::SphereSpec spec;
  spec.normalDeltas = false;
  const eng::Model model = vk_test::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Agreement a = compareWithCpu(model, *gpu, {variedWeights(4, 1.0f)});
  EXPECT_LE(a.maxNormalError, kNormalTolerance);
}

std::vector<std::filesystem::path> sharedModels() {
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"assets", "compressed"})  // compressed: meshopt / Draco variants
    for (const auto& entry : std::filesystem::recursive_directory_iterator(testing_support::sharedDir() / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
    }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(GpuMorph, AgreesWithCpuOnEverySharedAsset) {
  FACIAL_REQUIRE_SHARED();
  const std::vector<std::filesystem::path> files = sharedModels();
  ASSERT_GE(files.size(), 7u);
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    auto model = eng::loadModel(file);
    ASSERT_TRUE(model) << model.error().message;
    auto gpu = vk_test::renderer().upload(*model);
    ASSERT_TRUE(gpu) << gpu.error().message;
    const size_t count = gpu->weightCount();
    const Agreement a = compareWithCpu(*model, *gpu, {variedWeights(count, 0.0f), variedWeights(count, 1.3f)});
    EXPECT_GT(a.comparedPrimitives, 0u);
    EXPECT_LE(a.maxNormalError, kNormalTolerance);
    std::printf("  %s: %zu primitives x 2 instances, max position error %.2e x diagonal, normal error %.2e\n",
                file.filename().string().c_str(), a.comparedPrimitives / 2, a.maxPositionError, a.maxNormalError);
  }
}

}  // namespace
