// SculptModel / bakeSculptTarget / SculptPreview / ModelSurface on a small
// synthetic model whose node moves and scales it (so world and local space
// differ), plus the built-in head.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "editor/model_surface.h"
#include "editor/sculpt_model.h"
#include "engine/scene/cpu_morph.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using editor::ModelSurface;
using editor::SculptModel;

// A UV sphere of radius 1 on a node translated by (1, 2, 3) and scaled by 2,
// with one morph target "puff" that pushes every vertex out by 0.1 (local).
eng::Model sphereModel() {
  eng::Model model;
  model.sourcePath = "sphere (test)";
  eng::Primitive primitive;
  const int rings = 16, segments = 24;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = float(M_PI) * float(r) / rings, phi = 2.0f * float(M_PI) * float(s) / segments;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      primitive.positions.push_back(p);
      primitive.normals.push_back(p);
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
      primitive.indices.insert(primitive.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  eng::MorphTarget puff;
  for (const glm::vec3& p : primitive.positions) puff.positions.push_back(0.1f * p);
  puff.normals.assign(primitive.positions.size(), glm::vec3(0.0f));
  primitive.targets.push_back(std::move(puff));
  eng::Mesh mesh;
  mesh.name = "ball";
  mesh.primitives.push_back(std::move(primitive));
  mesh.targetNames = {"puff"};
  mesh.defaultWeights = {0.0f};
  model.meshes.push_back(std::move(mesh));
  eng::Node node;
  node.name = "ball";
  node.mesh = 0;
  node.translation = {1.0f, 2.0f, 3.0f};
  node.scale = glm::vec3(2.0f);
  model.nodes.push_back(node);
  model.roots = {0};
  eng::Animation animation;
  animation.name = "puff";
  animation.channels.push_back({0, 0, eng::Interpolation::Linear, 1, {0.0f, 1.0f}, {0.0f, 1.0f}});
  model.animations.push_back(animation);
  return model;
}

// World-space vertex `v` of the sphere's rest pose.
glm::vec3 worldVertex(const eng::Model& model, size_t v) {
  return glm::vec3(model.worldTransform(0) * glm::vec4(model.meshes[0].primitives[0].positions[v], 1.0f));
}

TEST(ModelSurface, RayHitsThePosedSurfaceAndReportsTheRestPoint) {
  const eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface) << surface.error().message;
  ASSERT_EQ(surface->vertexCount(), model.meshes[0].primitives[0].vertexCount());
  // From +Z toward the centre (1, 2, 3): the rest sphere (radius 2) is hit at z = 5.
  auto hit = surface->raycast(model, {1.0f, 2.0f, 20.0f}, {0.0f, 0.0f, -1.0f});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->posedPoint.z, 5.0f, 0.02f);
  // Puffed (radius 2.2 in world space): hit further out, rest point still on the rest sphere.
  const std::vector<float> puffed = {1.0f};
  ASSERT_TRUE(surface->pose(model, puffed));
  hit = surface->raycast(model, {1.0f, 2.0f, 20.0f}, {0.0f, 0.0f, -1.0f});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->posedPoint.z, 5.2f, 0.02f);
  EXPECT_NEAR(glm::distance(hit->restPoint, glm::vec3(1, 2, 3)), 2.0f, 0.02f);
  EXPECT_FALSE(surface->raycast(model, {10.0f, 2.0f, 20.0f}, {0.0f, 0.0f, -1.0f}));  // misses
  EXPECT_FALSE(surface->pose(model, std::vector<float>{1.0f, 2.0f}));                 // wrong size
}

TEST(SculptModel, InvalidPointsAndKernelsAreRejected) {
  const eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  EXPECT_FALSE(sculpt.prepare());  // no points
  EXPECT_FALSE(sculpt.addPoint("nan", {NAN, 0.0f, 0.0f}));
  ASSERT_TRUE(sculpt.addPoint("a", worldVertex(model, 30)));
  const auto twice = sculpt.addPoint("b", worldVertex(model, 30));
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().message.find("'a'"), std::string::npos) << twice.error().message;
  EXPECT_FALSE(sculpt.setDisplacement(0, {INFINITY, 0.0f, 0.0f}));
  EXPECT_FALSE(sculpt.setDisplacement(3, {0.0f, 0.0f, 0.0f}));
  EXPECT_FALSE(sculpt.setKernel({facial::RbfKernelType::Multiquadric, 1, 0.0f}));
  EXPECT_FALSE(sculpt.setKernel({facial::RbfKernelType::Polyharmonic, 0, 0.1f}));
  EXPECT_EQ(sculpt.kernel().type, facial::RbfKernelType::Biharmonic);
  // One point without pins cannot carry an RBF with an affine part.
  sculpt.setPinsEnabled(false);
  EXPECT_FALSE(sculpt.prepare());
  sculpt.setPinsEnabled(true);
  EXPECT_TRUE(sculpt.prepare());
}

TEST(SculptModel, TheSolveIsRefactoredOnlyWhenTheLayoutChanges) {
  const eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  ASSERT_TRUE(sculpt.addPoint("a", worldVertex(model, 40)));
  ASSERT_TRUE(sculpt.prepare());
  const uint64_t layout = sculpt.layoutRevision();
  ASSERT_TRUE(sculpt.setDisplacement(0, {0.0f, 0.1f, 0.0f}));
  EXPECT_EQ(sculpt.layoutRevision(), layout);
  EXPECT_TRUE(sculpt.prepared());
  ASSERT_TRUE(sculpt.setKernel({facial::RbfKernelType::Polyharmonic, 1, 0.1f}));
  EXPECT_NE(sculpt.layoutRevision(), layout);
  EXPECT_FALSE(sculpt.prepared());
}

class SculptBake : public ::testing::TestWithParam<facial::RbfKernel> {};

TEST_P(SculptBake, ReproducesTheDisplacementsAtTheControlPoints) {
  eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  ASSERT_TRUE(sculpt.setKernel(GetParam()));
  const std::vector<size_t> vertices = {30, 120, 200, 260, 333};
  const std::vector<glm::vec3> moves = {{0, 0.2f, 0}, {0.1f, 0, 0}, {0, 0, -0.15f}, {0, 0, 0}, {-0.05f, 0.05f, 0.05f}};
  for (size_t i = 0; i < vertices.size(); ++i) {
    auto index = sculpt.addPoint("p" + std::to_string(i), worldVertex(model, vertices[i]));
    ASSERT_TRUE(index) << index.error().message;
    ASSERT_TRUE(sculpt.setDisplacement(*index, moves[i]));
  }
  const auto baked = editor::bakeSculptTarget(model, *surface, sculpt, "sculpted");
  ASSERT_TRUE(baked) << baked.error().message;
  ASSERT_EQ(model.meshes[0].targetNames.size(), 2u);
  EXPECT_EQ(model.meshes[0].targetNames[1], "sculpted");
  EXPECT_EQ(model.meshes[0].defaultWeights.size(), 2u);
  const eng::MorphTarget& target = model.meshes[0].primitives[0].targets[1];
  const glm::mat3 linear(model.worldTransform(0));
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::vec3 world = linear * target.positions[vertices[i]];
    EXPECT_NEAR(glm::distance(world, moves[i]), 0.0f, 1e-4f) << "control point " << i;
  }
  // Vertices far from every moved point move less than the points themselves.
  EXPECT_LT(glm::length(linear * target.positions[400]), 0.2f);
  // The weight animation grew by one zero per key.
  EXPECT_EQ(model.animations[0].channels[0].targetCount, 2u);
  EXPECT_EQ(model.animations[0].channels[0].values, (std::vector<float>{0.0f, 0.0f, 1.0f, 0.0f}));
  // A second bake under the same name is refused.
  EXPECT_FALSE(editor::bakeSculptTarget(model, *surface, sculpt, "sculpted"));
  EXPECT_FALSE(editor::bakeSculptTarget(model, *surface, sculpt, ""));
}

INSTANTIATE_TEST_SUITE_P(Kernels, SculptBake,
                         ::testing::Values(facial::RbfKernel{facial::RbfKernelType::Biharmonic, 1, 0.1f},
                                           facial::RbfKernel{facial::RbfKernelType::Polyharmonic, 1, 0.1f},
                                           facial::RbfKernel{facial::RbfKernelType::Multiquadric, 1, 0.5f}));

TEST(SculptModel, NothingToBakeLeavesTheModelUntouched) {
  eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  ASSERT_TRUE(sculpt.addPoint("a", worldVertex(model, 30)));
  const auto nothing = editor::bakeSculptTarget(model, *surface, sculpt, "flat");
  ASSERT_FALSE(nothing);
  EXPECT_NE(nothing.error().message.find("nothing to bake"), std::string::npos) << nothing.error().message;
  EXPECT_EQ(model.meshes[0].targetNames.size(), 1u);
  EXPECT_EQ(model.meshes[0].primitives[0].targets.size(), 1u);
}

TEST(SculptModel, PreviewWeightsReproduceTheBakedTarget) {
  eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  ASSERT_TRUE(sculpt.addPoint("a", worldVertex(model, 60)));
  ASSERT_TRUE(sculpt.addPoint("b", worldVertex(model, 300)));
  ASSERT_TRUE(sculpt.setDisplacement(0, {0.0f, 0.3f, 0.1f}));
  ASSERT_TRUE(sculpt.setDisplacement(1, {-0.2f, 0.0f, 0.0f}));
  ASSERT_TRUE(sculpt.prepare());
  auto preview = editor::SculptPreview::build(model, *surface, sculpt);
  ASSERT_TRUE(preview) << preview.error().message;
  EXPECT_EQ(preview->weightCount(), 1u + 6u);
  std::vector<float> weights(preview->weightCount());
  const std::vector<float> face = {0.25f};
  ASSERT_TRUE(preview->weights(face, sculpt.points(), weights));
  EXPECT_FLOAT_EQ(weights[0], 0.25f);
  EXPECT_FALSE(preview->weights(std::vector<float>{1.0f, 2.0f}, sculpt.points(), weights));

  const eng::Primitive& previewPrimitive = preview->model().meshes[0].primitives[0];
  std::vector<glm::vec3> previewed(previewPrimitive.vertexCount());
  eng::morphPrimitiveCpu(previewPrimitive, weights, previewed, {});

  eng::Model baked = sphereModel();
  ASSERT_TRUE(editor::bakeSculptTarget(baked, *surface, sculpt, "s"));
  std::vector<glm::vec3> expected(previewed.size());
  eng::morphPrimitiveCpu(baked.meshes[0].primitives[0], std::vector<float>{0.25f, 1.0f}, expected, {});
  for (size_t v = 0; v < expected.size(); ++v) ASSERT_NEAR(glm::distance(previewed[v], expected[v]), 0.0f, 1e-5f) << v;
}

TEST(SculptModel, TheSavedGlbReloadsWithTheNewTarget) {
  const fs::path dir = testing_support::freshTempDir("editor_sculpt_glb");
  eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  ASSERT_TRUE(sculpt.addPoint("a", worldVertex(model, 100)));
  ASSERT_TRUE(sculpt.setDisplacement(0, {0.0f, 0.0f, 0.25f}));
  ASSERT_TRUE(editor::bakeSculptTarget(model, *surface, sculpt, "pout"));
  ASSERT_TRUE(eng::saveModel(model, dir / "ball.glb"));
  auto reloaded = eng::loadModel(dir / "ball.glb");
  ASSERT_TRUE(reloaded) << reloaded.error().message;
  ASSERT_EQ(reloaded->meshes.size(), 1u);
  EXPECT_EQ(reloaded->meshes[0].targetNames, (std::vector<std::string>{"puff", "pout"}));
  const auto& saved = model.meshes[0].primitives[0].targets[1].positions;
  const auto& loaded = reloaded->meshes[0].primitives[0].targets[1].positions;
  ASSERT_EQ(loaded.size(), saved.size());
  for (size_t v = 0; v < saved.size(); ++v) ASSERT_NEAR(glm::distance(loaded[v], saved[v]), 0.0f, 1e-6f) << v;
  const glm::vec3 world = glm::mat3(reloaded->worldTransform(0)) * loaded[100];
  EXPECT_NEAR(world.z, 0.25f, 1e-4f);
}

// A ray along the head's mirror plane runs exactly over the shared edges of
// the midline triangles, where rounding can put it outside both neighbours;
// the pick must still land on the front of the face (the editor's click on
// the nose once went through to the back of the head).
TEST(ModelSurface, RaysAlongTheMidlineSeamHitTheFrontOfTheFace) {
  auto model = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(model) << model.error().message;
  auto surface = ModelSurface::create(*model);
  ASSERT_TRUE(surface);
  int misses = 0, backHits = 0, rays = 0;
  // Slightly tilted rays, as from a perspective camera in front of the face.
  for (float y = -0.06f; y <= 0.06f; y += 0.0025f)
    for (const float tilt : {-0.08f, -0.03f, 0.0f, 0.03f, 0.08f}) {
      const glm::vec3 origin{0.0f, y, 0.28f};
      const glm::vec3 direction = glm::normalize(glm::vec3(0.0f, tilt, -1.0f));
      ++rays;
      const auto hit = surface->raycast(*model, origin, direction);
      if (!hit) ++misses;
      else if (hit->restPoint.z < 0.0f) ++backHits;
    }
  EXPECT_EQ(misses, 0) << "of " << rays;
  EXPECT_EQ(backHits, 0) << "of " << rays << " midline rays went through the face to the back of the head";
}

TEST(SculptModel, BuiltInHeadBakesAcrossAllItsPrimitives) {
  auto model = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(model) << model.error().message;
  auto surface = ModelSurface::create(*model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model->bounds());
  // Click the nose tip from the front.
  const eng::Aabb bounds = model->bounds();
  auto hit = surface->raycast(*model, {0.0f, -0.0215f, bounds.max.z + 1.0f}, {0.0f, 0.0f, -1.0f});
  ASSERT_TRUE(hit);
  EXPECT_GT(hit->restPoint.z, bounds.max.z - 0.02f) << "the front of the face, not the back of the head";
  ASSERT_TRUE(sculpt.addPoint("nose_tip", hit->restPoint));
  ASSERT_TRUE(sculpt.setDisplacement(0, {0.0f, 0.0f, 0.01f}));
  const size_t targetsBefore = model->meshes[0].targetNames.size();
  const auto baked = editor::bakeSculptTarget(*model, *surface, sculpt, "long_nose");
  ASSERT_TRUE(baked) << baked.error().message;
  for (const eng::Mesh& mesh : model->meshes)
    for (const eng::Primitive& primitive : mesh.primitives) EXPECT_EQ(primitive.targets.size(), mesh.targetNames.size());
  EXPECT_EQ(model->meshes[0].targetNames.size(), targetsBefore + 1);
}

}  // namespace

namespace {

TEST(SculptModel, FalloffKeepsTheEditLocalAndThePreviewAgrees) {
  eng::Model model = sphereModel();
  auto surface = ModelSurface::create(model);
  ASSERT_TRUE(surface);
  SculptModel sculpt(surface->restPositions(), model.bounds());
  const glm::vec3 picked = worldVertex(model, 60);
  ASSERT_TRUE(sculpt.addPoint("a", picked));
  ASSERT_TRUE(sculpt.setDisplacement(0, {0.0f, 0.3f, 0.0f}));
  ASSERT_TRUE(sculpt.prepare());
  std::vector<glm::vec3> global(surface->restPositions().size());
  ASSERT_TRUE(sculpt.vertexDisplacements(global));

  const uint64_t before = sculpt.layoutRevision();
  ASSERT_TRUE(sculpt.setFalloffRadius(1.0f));  // the sphere is 4 units across
  EXPECT_GT(sculpt.layoutRevision(), before) << "a new falloff re-prepares";
  ASSERT_TRUE(sculpt.prepare());
  std::vector<glm::vec3> local(global.size());
  ASSERT_TRUE(sculpt.vertexDisplacements(local));
  size_t far = 0;
  for (size_t v = 0; v < local.size(); ++v) {
    const float d = glm::distance(surface->restPositions()[v], picked);
    if (d <= 0.5f) {
      EXPECT_NEAR(glm::distance(local[v], global[v]), 0.0f, 1e-6f) << "inside half the radius: unchanged";
    }
    if (d >= 1.0f) {
      EXPECT_EQ(local[v], glm::vec3(0.0f)) << "beyond the radius nothing moves";
      far += glm::length(global[v]) > 1e-4f;  // ...where the unmasked field did move it
    }
  }
  EXPECT_GT(far, 10u);

  // The preview basis carries the same falloff as the baked target.
  auto preview = editor::SculptPreview::build(model, *surface, sculpt);
  ASSERT_TRUE(preview) << preview.error().message;
  std::vector<float> weights(preview->weightCount());
  ASSERT_TRUE(preview->weights(std::vector<float>{0.0f}, sculpt.points(), weights));
  const eng::Primitive& previewPrimitive = preview->model().meshes[0].primitives[0];
  std::vector<glm::vec3> previewed(previewPrimitive.vertexCount());
  eng::morphPrimitiveCpu(previewPrimitive, weights, previewed, {});
  eng::Model baked = sphereModel();
  ASSERT_TRUE(editor::bakeSculptTarget(baked, *surface, sculpt, "local"));
  std::vector<glm::vec3> expected(previewed.size());
  eng::morphPrimitiveCpu(baked.meshes[0].primitives[0], std::vector<float>{0.0f, 1.0f}, expected, {});
  for (size_t v = 0; v < expected.size(); ++v) ASSERT_NEAR(glm::distance(previewed[v], expected[v]), 0.0f, 1e-5f) << v;

  EXPECT_FALSE(sculpt.setFalloffRadius(-1.0f));
  EXPECT_FALSE(sculpt.setFalloffRadius(std::nanf("")));
  EXPECT_FLOAT_EQ(sculpt.falloffRadius(), 1.0f);
}

}  // namespace
