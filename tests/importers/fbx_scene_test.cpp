// Reading FBX scenes (importers/fbx_scene.h) against another reader's idea of
// the same scene: tests/importers/fbx/rigged_face.{fbx,glb} were both written
// by Blender from one scene (make_rigged_face.py there), so the FBX importer
// and the glTF loader must place, skin, morph and texture every vertex alike.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/skeleton_pose.h"
#include "engine/scene/skinning.h"
#include "importers/load_face.h"
#include "tests/common/fbx_test_files.h"
#include "tests/common/test_support.h"

// Named, so that its helpers do not meet other files' in a unity build.
namespace fbx_scene_test {
namespace {

namespace fs = std::filesystem;

const fs::path kFiles = testing_support::sourceDir() / "tests" / "importers" / "fbx";

struct PlacedVertex {
  glm::vec3 position, normal;
  glm::vec2 uv;
  int material;
};

// Every vertex of the mesh drawn by the node called `nodeName`, morphed by
// `weights` (by target name; the rest at their defaults), skinned in `pose`
// and placed in the world.
std::vector<PlacedVertex> placedVertices(const eng::Model& model, const eng::Pose& pose, const std::string& nodeName,
                                         const std::map<std::string, float>& weights = {}) {
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, pose, world);
  std::vector<PlacedVertex> out;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const eng::Node& node = model.nodes[n];
    if (node.name != nodeName || node.mesh < 0) continue;
    const eng::Mesh& mesh = model.meshes[size_t(node.mesh)];
    std::vector<float> meshWeights = mesh.defaultWeights;
    for (size_t t = 0; t < mesh.targetNames.size(); ++t)
      if (const auto it = weights.find(mesh.targetNames[t]); it != weights.end()) meshWeights[t] = it->second;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world[n])));
    for (const eng::Primitive& p : mesh.primitives) {
      std::vector<glm::vec3> positions(p.vertexCount()), normals(p.vertexCount());
      EXPECT_TRUE(eng::posePrimitiveCpu(model, int(n), p, meshWeights, world, positions, normals));
      for (size_t v = 0; v < positions.size(); ++v)
        out.push_back({glm::vec3(world[n] * glm::vec4(positions[v], 1.0f)), glm::normalize(normalMatrix * normals[v]),
                       v < p.texcoords.size() ? p.texcoords[v] : glm::vec2(-1.0f), p.material});
    }
  }
  return out;
}

// The largest distance from a vertex of `a` to the nearest vertex of `b`
// with the same texture coordinate (seams split vertices differently).
float farthestFromItsTwin(const std::vector<PlacedVertex>& a, const std::vector<PlacedVertex>& b) {
  float worst = 0.0f;
  for (const PlacedVertex& v : a) {
    float best = 1e30f;
    for (const PlacedVertex& w : b)
      if (glm::distance(v.uv, w.uv) < 1e-4f) best = std::min(best, glm::distance(v.position, w.position));
    worst = std::max(worst, best);
  }
  return worst;
}

struct BothFiles {
  eng::Model fbx, gltf;
};

BothFiles loadBoth() {
  auto fbx = importers::loadFace(kFiles / "rigged_face.fbx");
  auto gltf = importers::loadFace(kFiles / "rigged_face.glb");
  EXPECT_TRUE(fbx) << fbx.error().message;
  EXPECT_TRUE(gltf) << gltf.error().message;
  if (!fbx || !gltf) return {};
  EXPECT_EQ(fbx->format, importers::FaceFormat::Fbx);
  return {std::move(fbx->model), std::move(gltf->model)};
}

TEST(FbxScene, BlendersFbxPlacesEveryVertexWhereItsGltfDoes) {
  const BothFiles both = loadBoth();
  ASSERT_FALSE(both.fbx.meshes.empty());
  const eng::Pose fbxRest = eng::restPose(both.fbx), gltfRest = eng::restPose(both.gltf);
  for (const char* node : {"Face", "Hat"}) {
    const auto fbx = placedVertices(both.fbx, fbxRest, node);
    const auto gltf = placedVertices(both.gltf, gltfRest, node);
    ASSERT_EQ(fbx.size(), gltf.size()) << node;
    ASSERT_FALSE(fbx.empty()) << node;
    // The scene is about 3 m across; Blender writes floats.
    EXPECT_LT(farthestFromItsTwin(fbx, gltf), 1e-4f) << node << ": skinned (Face) or placed by its parents (Hat)";
    EXPECT_LT(farthestFromItsTwin(gltf, fbx), 1e-4f) << node;
    // Flat-shaded faces share a position and texture coordinate with their
    // neighbours: a twin has the normal too.
    size_t withTwin = 0;
    for (const PlacedVertex& v : fbx) {
      bool found = false;
      for (const PlacedVertex& w : gltf)
        found |= glm::distance(v.uv, w.uv) < 1e-4f && glm::distance(v.position, w.position) < 1e-4f && glm::dot(v.normal, w.normal) > 0.999f;
      withTwin += found;
    }
    EXPECT_EQ(withTwin, fbx.size()) << node << ": the file's normals, turned with the vertex";
  }
}

TEST(FbxScene, BlendShapesBecomeNamedTargetsWithTheirDefaultWeights) {
  const BothFiles both = loadBoth();
  ASSERT_FALSE(both.fbx.meshes.empty());
  const eng::Mesh* face = nullptr;
  for (const eng::Mesh& m : both.fbx.meshes)
    if (m.name == "Face") face = &m;
  ASSERT_NE(face, nullptr);
  EXPECT_EQ(face->targetNames, (std::vector<std::string>{"jawOpen", "mouthSmile_L"})) << "the channels' names, as a rig matches them";
  EXPECT_FLOAT_EQ(face->defaultWeights[0], 0.25f) << "DeformPercent 25";
  const eng::Pose fbxRest = eng::restPose(both.fbx), gltfRest = eng::restPose(both.gltf);
  for (const std::map<std::string, float>& weights :
       {std::map<std::string, float>{{"jawOpen", 1.0f}}, {{"jawOpen", 0.0f}, {"mouthSmile_L", 1.0f}}}) {
    const auto fbx = placedVertices(both.fbx, fbxRest, "Face", weights);
    const auto gltf = placedVertices(both.gltf, gltfRest, "Face", weights);
    EXPECT_LT(farthestFromItsTwin(fbx, gltf), 1e-4f) << weights.begin()->first;
  }
  // And the shapes do move it: the jaw fully open is not the rest.
  const auto open = placedVertices(both.fbx, fbxRest, "Face", {{"jawOpen", 1.0f}});
  const auto rest = placedVertices(both.fbx, fbxRest, "Face", {{"jawOpen", 0.0f}});
  float moved = 0.0f;
  for (size_t v = 0; v < open.size(); ++v) moved = std::max(moved, glm::distance(open[v].position, rest[v].position));
  EXPECT_GT(moved, 0.3f) << "0.25 in the rig's space, scaled 1.5 by its object";
}

TEST(FbxScene, SkinnedVerticesFollowATurnedBone) {
  const BothFiles both = loadBoth();
  ASSERT_FALSE(both.fbx.meshes.empty());
  eng::Pose fbxPose = eng::restPose(both.fbx), gltfPose = eng::restPose(both.gltf);
  // The same turn of the Head bone in each file's own bone space.
  auto turnHead = [](const eng::Model& model, eng::Pose& pose) {
    for (size_t n = 0; n < model.nodes.size(); ++n)
      if (model.nodes[n].name == "Head") pose.rotations[n] = pose.rotations[n] * glm::angleAxis(0.6f, glm::vec3(1, 0, 0));
  };
  turnHead(both.fbx, fbxPose);
  turnHead(both.gltf, gltfPose);
  const auto fbx = placedVertices(both.fbx, fbxPose, "Face");
  const auto gltf = placedVertices(both.gltf, gltfPose, "Face");
  const auto rest = placedVertices(both.fbx, eng::restPose(both.fbx), "Face");
  float moved = 0.0f;
  for (size_t v = 0; v < fbx.size(); ++v) moved = std::max(moved, glm::distance(fbx[v].position, rest[v].position));
  EXPECT_GT(moved, 0.3f) << "the turn moves the face";
  EXPECT_LT(farthestFromItsTwin(fbx, gltf), 1e-3f) << "bind matrices and bone spaces as Blender's glTF has them";
}

TEST(FbxScene, MaterialsKeepTheirColourAndEmbeddedTexture) {
  const BothFiles both = loadBoth();
  ASSERT_EQ(both.fbx.materials.size(), 2u);
  ASSERT_EQ(both.gltf.materials.size(), 2u);
  for (size_t m = 0; m < 2; ++m) {
    const eng::Material& a = both.fbx.materials[m];
    const eng::Material& b = both.gltf.materials[m];
    EXPECT_EQ(a.name, b.name);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.baseColorFactor[c], b.baseColorFactor[c], 1e-3f) << a.name;
    EXPECT_NEAR(a.roughness, b.roughness, 1e-3f) << a.name << ": from the Phong exponent, as Blender writes it";
    ASSERT_EQ(a.baseColorImage >= 0, b.baseColorImage >= 0) << a.name;
    if (a.baseColorImage < 0) continue;
    const eng::Image& ai = both.fbx.images[size_t(a.baseColorImage)];
    const eng::Image& bi = both.gltf.images[size_t(b.baseColorImage)];
    EXPECT_EQ(ai.width, bi.width);
    EXPECT_EQ(ai.rgba8, bi.rgba8) << "the 4x4 texels, embedded in the FBX";
  }
  // Texture coordinates: V flipped from FBX's up to glTF's down, as the glTF has them.
  const eng::Pose fbxRest = eng::restPose(both.fbx), gltfRest = eng::restPose(both.gltf);
  const auto fbx = placedVertices(both.fbx, fbxRest, "Face");
  const auto gltf = placedVertices(both.gltf, gltfRest, "Face");
  size_t twins = 0;
  for (const PlacedVertex& v : fbx)
    for (const PlacedVertex& w : gltf)
      twins += glm::distance(v.position, w.position) < 1e-4f && glm::distance(v.uv, w.uv) < 1e-5f && v.material == w.material;
  EXPECT_GE(twins, fbx.size()) << "each vertex has a twin with its position, texture coordinate and material";
}

// Every animation of `model` at `time`: the nodes' channels into `pose`, the
// weights (linear, as both files key them) by target name.
std::map<std::string, float> sampleAll(const eng::Model& model, float time, eng::Pose& pose) {
  std::map<std::string, float> weights;
  for (const eng::Animation& animation : model.animations) {
    eng::sampleAnimation(animation, time, pose);
    for (const eng::WeightsChannel& c : animation.channels) {
      if (c.times.empty()) continue;
      size_t k = 0;
      while (k + 1 < c.times.size() && c.times[k + 1] <= time) ++k;
      const size_t next = std::min(k + 1, c.times.size() - 1);
      const float f = next == k ? 0.0f : std::clamp((time - c.times[k]) / (c.times[next] - c.times[k]), 0.0f, 1.0f);
      for (size_t t = 0; t < c.targetCount; ++t)
        weights[model.meshes[size_t(c.mesh)].targetNames[t]] =
            c.values[k * c.targetCount + t] + f * (c.values[next * c.targetCount + t] - c.values[k * c.targetCount + t]);
    }
  }
  return weights;
}

TEST(FbxScene, BakedAnimationPlaysAsItsGltfDoes) {
  // animated_face: the jaw and smile keyed, the Head bone nodding and lifting,
  // baked by Blender into both files (24 frames a second, frames 1 to 25).
  auto fbx = importers::loadFace(kFiles / "animated_face.fbx");
  auto gltf = importers::loadFace(kFiles / "animated_face.glb");
  ASSERT_TRUE(fbx) << fbx.error().message;
  ASSERT_TRUE(gltf) << gltf.error().message;
  ASSERT_EQ(fbx->model.animations.size(), 1u) << "one AnimationStack";
  const eng::Animation& clip = fbx->model.animations[0];
  EXPECT_EQ(clip.name, "Scene");
  EXPECT_NEAR(clip.duration(), 25.0f / 24.0f, 1e-4f) << "key times in seconds, as the glTF has them";
  ASSERT_EQ(clip.channels.size(), 1u) << "the Face's blend shapes";
  EXPECT_EQ(clip.channels[0].times.size(), 25u);
  for (float time : {0.1f, 0.3f, 0.45f, 0.6f, 0.8f, 1.0f}) {
    eng::Pose fbxPose = eng::restPose(fbx->model), gltfPose = eng::restPose(gltf->model);
    const auto fbxWeights = sampleAll(fbx->model, time, fbxPose);
    const auto gltfWeights = sampleAll(gltf->model, time, gltfPose);
    for (const char* target : {"jawOpen", "mouthSmile_L"}) {
      ASSERT_TRUE(fbxWeights.count(target)) << target;
      EXPECT_NEAR(fbxWeights.at(target), gltfWeights.at(target), 1e-4f) << target << " at " << time;
    }
    for (const char* node : {"Face", "Hat"}) {
      const auto a = placedVertices(fbx->model, fbxPose, node, fbxWeights);
      const auto b = placedVertices(gltf->model, gltfPose, node, gltfWeights);
      EXPECT_LT(farthestFromItsTwin(a, b), 1e-3f) << node << " at " << time;
    }
  }
  // The nod does move the face.
  eng::Pose rest = eng::restPose(fbx->model), nodding = eng::restPose(fbx->model);
  sampleAll(fbx->model, 0.5f, nodding);
  const auto a = placedVertices(fbx->model, rest, "Face"), b = placedVertices(fbx->model, nodding, "Face");
  float moved = 0.0f;
  for (size_t v = 0; v < a.size(); ++v) moved = std::max(moved, glm::distance(a[v].position, b[v].position));
  EXPECT_GT(moved, 0.3f);
}

TEST(FbxScene, PivotsOffsetsPreAndPostRotationsOrdersAndGeometricTransformsPlaceAsBlenderReadsThem) {
  // pivots.fbx: written by Blender's FBX encoder with every part of the FBX
  // SDK's transform; pivots.glb: Blender's reading of it (make_pivots.py).
  auto fbx = importers::loadFace(kFiles / "pivots.fbx");
  auto gltf = importers::loadFace(kFiles / "pivots.glb");
  ASSERT_TRUE(fbx) << fbx.error().message;
  ASSERT_TRUE(gltf) << gltf.error().message;
  EXPECT_TRUE(fbx->model.warnings.empty()) << fbx->model.warnings.front();
  const eng::Pose fbxRest = eng::restPose(fbx->model), gltfRest = eng::restPose(gltf->model);
  // Box: under a parent with every pivot and offset, its own post-rotation and geometric transform;
  // Plain: pre-rotation and order written with RotationActive off, so ignored.
  for (const char* node : {"Box", "Plain"}) {
    const auto a = placedVertices(fbx->model, fbxRest, node);
    const auto b = placedVertices(gltf->model, gltfRest, node);
    ASSERT_EQ(a.size(), 8u) << node;
    ASSERT_EQ(b.size(), 8u) << node;
    EXPECT_LT(farthestFromItsTwin(a, b), 1e-4f) << node;
    EXPECT_LT(farthestFromItsTwin(b, a), 1e-4f) << node;
  }
}

TEST(FbxScene, TheBuiltInHeadAsAnFbxOfItsPrimitivesMatchesIt) {
  // An FBX written by the tests' own writer (zlib arrays, normals by polygon
  // vertex, texture coordinates by vertex, metres): what a face without
  // targets brings, read back to the same surface.
  auto head = importers::loadFace(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(head) << head.error().message;
  const fs::path dir = testing_support::freshTempDir("fbx_head");
  testing_support::writeFile(dir / "head.fbx", testing_support::modelAsFbx(head->model));
  auto fbx = importers::loadFace(dir / "head.fbx");
  ASSERT_TRUE(fbx) << fbx.error().message;
  EXPECT_TRUE(importers::isPlainMesh(fbx->format)) << "autorig rigs it";
  const eng::Aabb a = head->model.bounds(), b = fbx->model.bounds();
  EXPECT_LT(glm::distance(a.min, b.min) + glm::distance(a.max, b.max), 1e-5f);
  EXPECT_EQ(fbx->model.totalVertexCount(), head->model.totalVertexCount()) << "corners that agree share a vertex again";
}

}  // namespace
}  // namespace fbx_scene_test
