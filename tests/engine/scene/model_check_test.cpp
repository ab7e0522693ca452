// eng::checkModel: every rule, each refusal by its whole message (the element
// by index and name, and the sizes that disagree), with and without what a
// GPU upload additionally needs.
#include "engine/scene/model_check.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A small model that uses every part checkModel looks at: an image, a
// material with a detail layer, a skinned mesh with a morph target drawn by a
// child node, a skin, and an animation with a node and a weights channel.
eng::Model everyPart() {
  eng::Model model;
  model.images.push_back({.name = "skin", .width = 2, .height = 1, .rgba8 = std::vector<uint8_t>(8, 255)});
  model.materials.push_back({.name = "face", .baseColorImage = 0, .detailLayers = {{0, "smile", 1.0f}}});
  eng::Primitive prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  prim.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  prim.texcoords = {{0, 0}, {1, 0}, {0, 1}};
  prim.tangents = {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}};
  prim.colors = {glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(1.0f)};
  prim.indices = {0, 1, 2};
  prim.material = 0;
  prim.joints = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  prim.jointWeights = {{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  prim.targets.push_back({.positions = {{0, 0, 0.1f}, {0, 0, 0}, {0, 0, 0}},
                          .normals = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                          .tangents = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}});
  model.meshes.push_back({.name = "head", .primitives = {prim}, .targetNames = {"smile"}, .defaultWeights = {0.0f}});
  eng::Node root{.name = "root", .children = {1}};
  eng::Node face{.name = "face", .parent = 0, .mesh = 0, .skin = 0};
  model.nodes = {root, face};
  model.roots = {0};
  model.skins.push_back({.name = "rig", .joints = {0}, .inverseBindMatrices = {glm::mat4(1.0f)}});
  eng::Animation talk{.name = "talk"};
  talk.nodeChannels.push_back({.node = 0, .times = {0.0f}, .values = {0, 0, 0}});
  talk.channels.push_back({.node = 1, .mesh = 0, .targetCount = 1, .times = {0.0f}, .values = {0.5f}});
  model.animations.push_back(talk);
  return model;
}

eng::Primitive& primitive(eng::Model& model) { return model.meshes[0].primitives[0]; }

TEST(ModelCheck, ModelWithEveryPartPassesForFileAndGpu) {
  const eng::Model model = everyPart();
  const auto forFile = eng::checkModel(model);
  EXPECT_TRUE(forFile) << forFile.error().message;
  const auto forGpu = eng::checkModel(model, eng::ModelCheck::gpuUpload());
  EXPECT_TRUE(forGpu) << forGpu.error().message;
}

// What glTF lets a file leave out: no normals, no indices, no inverse bind
// matrices (identity), no texcoords, tangents or colours.
TEST(ModelCheck, WhatAFileMayLeaveOutPasses) {
  eng::Model model = everyPart();
  eng::Primitive& prim = primitive(model);
  prim.normals.clear();
  prim.indices.clear();
  prim.texcoords.clear();
  prim.tangents.clear();
  prim.colors.clear();
  model.skins[0].inverseBindMatrices.clear();
  const auto ok = eng::checkModel(model);
  EXPECT_TRUE(ok) << ok.error().message;
}

struct Refusal {
  const char* rule;
  std::function<void(eng::Model&)> breakIt;
  std::string message;
  eng::ModelCheck needs = {};
};

const std::string kPrim = "mesh 0 'head' primitive 0";

std::vector<Refusal> refusals() {
  const eng::ModelCheck gpu = eng::ModelCheck::gpuUpload();
  return {
      {"image bytes", [](eng::Model& m) { m.images[0].rgba8.pop_back(); }, "image 0 'skin' is 2x1 with 7 RGBA8 bytes"},
      {"image size", [](eng::Model& m) { m.images[0].width = 0; }, "image 0 'skin' is 0x1 with 8 RGBA8 bytes"},
      {"base colour image", [](eng::Model& m) { m.materials[0].baseColorImage = 3; },
       "material 0 'face' base colour uses image 3 of 1 images"},
      {"detail layer image", [](eng::Model& m) { m.materials[0].detailLayers[0].image = -1; },
       "material 0 'face' detail layer 0 'smile' uses image -1 of 1 images"},
      {"default weights", [](eng::Model& m) { m.meshes[0].defaultWeights.push_back(0.0f); },
       "mesh 0 'head' has 2 default weights for 1 targets"},
      {"no vertices", [](eng::Model& m) { primitive(m) = {}; }, kPrim + " has no vertices"},
      {"too many vertices", [](eng::Model&) {}, kPrim + " has 3 vertices, more than the 2 a primitive may have here",
       {.maxVertices = 2}},
      {"normals", [](eng::Model& m) { primitive(m).normals.pop_back(); }, kPrim + " has 2 normals for 3 vertices"},
      {"normals for the GPU", [](eng::Model& m) { primitive(m).normals.clear(); }, kPrim + " has 0 normals for 3 vertices",
       gpu},
      {"texcoords", [](eng::Model& m) { primitive(m).texcoords.pop_back(); }, kPrim + " has 2 texcoords for 3 vertices"},
      {"tangents", [](eng::Model& m) { primitive(m).tangents.pop_back(); }, kPrim + " has 2 tangents for 3 vertices"},
      {"colors", [](eng::Model& m) { primitive(m).colors.pop_back(); }, kPrim + " has 2 colors for 3 vertices"},
      {"non-finite position", [](eng::Model& m) { primitive(m).positions[1].y = kNaN; }, kPrim + " has non-finite vertex data"},
      {"non-finite colour", [](eng::Model& m) { primitive(m).colors[2].a = kNaN; }, kPrim + " has non-finite vertex data"},
      {"joint groups", [](eng::Model& m) { primitive(m).jointWeights.pop_back(); },
       kPrim + " has 3 joint groups and 2 weight groups for 3 vertices"},
      {"non-finite joint weight", [](eng::Model& m) { primitive(m).jointWeights[0].x = kNaN; },
       kPrim + " has non-finite joint weights"},
      {"no indices for the GPU", [](eng::Model& m) { primitive(m).indices.clear(); },
       kPrim + " has no indices (drawn as an indexed triangle list)", gpu},
      {"not triangles", [](eng::Model& m) { primitive(m).indices.push_back(0); }, kPrim + " has 4 indices, not a multiple of 3"},
      {"index range", [](eng::Model& m) { primitive(m).indices[1] = 9; },
       kPrim + ": index 9 at position 1 is out of range of 3 vertices"},
      {"material", [](eng::Model& m) { primitive(m).material = 1; }, kPrim + " uses material 1 of 1 materials"},
      {"target count", [](eng::Model& m) { primitive(m).targets.emplace_back(); },
       kPrim + " has 2 morph targets, its mesh names 1"},
      {"position deltas", [](eng::Model& m) { primitive(m).targets[0].positions.pop_back(); },
       kPrim + " target 0 has 2 position deltas for 3 vertices"},
      {"normal deltas", [](eng::Model& m) { primitive(m).targets[0].normals.pop_back(); },
       kPrim + " target 0 has 2 normal deltas for 3 vertices"},
      {"tangent deltas", [](eng::Model& m) { primitive(m).targets[0].tangents.pop_back(); },
       kPrim + " target 0 has 2 tangent deltas for 3 vertices"},
      {"non-finite delta", [](eng::Model& m) { primitive(m).targets[0].positions[0].z = kNaN; },
       kPrim + " target 0 has non-finite deltas"},
      {"node mesh", [](eng::Model& m) { m.nodes[1].mesh = 2; }, "node 1 'face' uses mesh 2 of 1 meshes"},
      {"child link", [](eng::Model& m) { m.nodes[1].parent = -1; }, "node 0 'root' lists child 1 whose parent is not 0 (2 nodes)"},
      {"parent range", [](eng::Model& m) { m.nodes[1].parent = 5; }, "node 0 'root' lists child 1 whose parent is not 0 (2 nodes)"},
      {"parent range, no child link",
       [](eng::Model& m) {
         m.nodes[0].children.clear();
         m.nodes[1].parent = 5;
       },
       "node 1 'face' has parent 5 of 2 nodes"},
      {"node skin", [](eng::Model& m) { m.nodes[1].skin = 1; }, "node 1 'face' uses skin 1 of 1 skins"},
      {"non-finite translation", [](eng::Model& m) { m.nodes[0].translation.x = kNaN; }, "node 0 'root' has a non-finite transform"},
      {"non-finite matrix", [](eng::Model& m) { m.nodes[1].matrix[3][0] = kNaN; }, "node 1 'face' has a non-finite transform"},
      {"root with a parent", [](eng::Model& m) { m.roots = {1}; }, "root 1 is not a parentless node of 2"},
      {"root range", [](eng::Model& m) { m.roots = {4}; }, "root 4 is not a parentless node of 2"},
      {"skin joint", [](eng::Model& m) { m.skins[0].joints = {0, 2}; }, "skin 0 'rig' has joint node 2 of 2 nodes"},
      {"inverse bind matrices",
       [](eng::Model& m) {
         m.skins[0].joints = {0, 1};
       },
       "skin 0 'rig' has 1 inverse bind matrices for 2 joints"},
      {"non-finite inverse bind matrix", [](eng::Model& m) { m.skins[0].inverseBindMatrices[0][1][1] = kNaN; },
       "skin 0 'rig' has a non-finite inverse bind matrix"},
      {"node channel node", [](eng::Model& m) { m.animations[0].nodeChannels[0].node = 2; },
       "animation 0 'talk' node channel 0 targets node 2 of 2"},
      {"node channel values", [](eng::Model& m) { m.animations[0].nodeChannels[0].values.push_back(0.0f); },
       "animation 0 'talk' node channel 0 has 4 values for 1 keys of 3"},
      {"node channel without keys",
       [](eng::Model& m) {
         m.animations[0].nodeChannels[0].times.clear();
         m.animations[0].nodeChannels[0].values.clear();
       },
       "animation 0 'talk' node channel 0 has 0 values for 0 keys of 3"},
      {"weights channel node", [](eng::Model& m) { m.animations[0].channels[0].node = 0; },
       "animation 0 'talk' channel 0 targets node 0 / mesh 0, which do not match"},
      {"weights channel target count", [](eng::Model& m) { m.animations[0].channels[0].targetCount = 2; },
       "animation 0 'talk' channel 0 has 2 weights per key, the mesh has 1 targets"},
      {"weights channel values",
       [](eng::Model& m) { m.animations[0].channels[0].interpolation = eng::Interpolation::CubicSpline; },
       "animation 0 'talk' channel 0 has 1 values for 1 keys of 3"},
  };
}

TEST(ModelCheckValidity, EveryRuleRefusesWithItsMessage) {
  for (const Refusal& refusal : refusals()) {
    SCOPED_TRACE(refusal.rule);
    eng::Model model = everyPart();
    refusal.breakIt(model);
    const auto checked = eng::checkModel(model, refusal.needs);
    ASSERT_FALSE(checked);
    EXPECT_EQ(checked.error().kind, eng::ErrorKind::Malformed);
    EXPECT_EQ(checked.error().message, refusal.message);
  }
}

// What only a GPU upload asks for is refused there and nowhere else.
TEST(ModelCheckValidity, GpuUploadAddsNormalsIndicesAndAVertexLimit) {
  const eng::ModelCheck gpu = eng::ModelCheck::gpuUpload();
  EXPECT_TRUE(gpu.requireNormals);
  EXPECT_TRUE(gpu.requireIndices);
  EXPECT_EQ(gpu.maxVertices, size_t{UINT32_MAX / 4});
  EXPECT_EQ(eng::ModelCheck{}.maxVertices, std::numeric_limits<size_t>::max());

  eng::Model noNormals = everyPart();
  primitive(noNormals).normals.clear();
  EXPECT_TRUE(eng::checkModel(noNormals));
  EXPECT_FALSE(eng::checkModel(noNormals, gpu));

  eng::Model noIndices = everyPart();
  primitive(noIndices).indices.clear();
  EXPECT_TRUE(eng::checkModel(noIndices));
  EXPECT_FALSE(eng::checkModel(noIndices, gpu));
}

}  // namespace
