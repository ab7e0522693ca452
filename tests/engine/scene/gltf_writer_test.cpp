// glTF export: save -> load reproduces the Model (GLB and .gltf + .bin),
// sparse accessors for targets that move few vertices, 256 targets, and
// refusal of inconsistent models.
#include <fstream>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using testing_support::freshTempDir;
using Json = nlohmann::json;

// A small model touching every field the writer handles.
eng::Model richModel() {
  eng::Model model;
  eng::Image img;
  img.name = "checker";
  img.width = 2;
  img.height = 1;
  img.rgba8 = {255, 0, 0, 255, 0, 0, 255, 128};
  model.images.push_back(img);
  img.name = "freckles";
  img.rgba8 = {10, 20, 30, 40, 50, 60, 70, 80};
  model.images.push_back(img);

  eng::Material skin;
  skin.name = "skin";
  skin.baseColorFactor = {0.9f, 0.7f, 0.6f, 1.0f};
  skin.baseColorImage = 0;
  skin.roughness = 0.45f;
  skin.metallic = 0.05f;
  skin.doubleSided = true;
  skin.alphaMode = eng::AlphaMode::Mask;
  skin.alphaCutoff = 0.3f;
  skin.unlit = true;
  skin.emissiveFactor = {0.25f, 0.0f, 0.5f};
  skin.detailLayers.push_back({1, "smile", 0.8f});
  skin.detailLayers.push_back({1, "frown", 1.0f, eng::DetailBlend::Modulate});
  skin.metallicRoughnessImage = 1;
  skin.normalImage = 1;
  skin.normalScale = 0.5f;
  skin.occlusionImage = 0;
  skin.occlusionStrength = 0.75f;
  skin.occlusionSampling.wrapT = eng::TextureWrap::ClampToEdge;
  skin.emissiveImage = 0;
  skin.baseColorSampling = {eng::TextureWrap::ClampToEdge, eng::TextureWrap::MirroredRepeat, eng::TextureFilter::Nearest,
                            eng::TextureFilter::Nearest, false, eng::TextureFilter::Linear};
  model.materials.push_back(skin);
  model.materials.push_back(eng::Material{.name = "plain"});
  // The same image through another sampling: a second texture of one image.
  eng::Material decal{.name = "decal", .baseColorImage = 0};
  decal.baseColorSampling.mipFilter = eng::TextureFilter::Nearest;
  decal.metallicRoughnessImage = 0;  // the base colour's image, its texture with another sampling
  decal.metallicRoughnessSampling.wrapS = eng::TextureWrap::ClampToEdge;
  decal.toon = eng::ToonShading{.shadeColor = {0.5f, 0.25f, 0.125f}, .shadeFromBaseTexture = true, .shadingShift = -0.25f,
                                .shadingToony = 0.75f, .giEqualization = 0.5f, .rimColor = {0.0f, 0.5f, 1.0f},
                                .rimFresnelPower = 3.0f, .rimLift = 0.125f, .rimLightingMix = 0.5f,
                                .outlineMode = eng::ToonShading::OutlineWidth::Screen, .outlineWidth = 0.0078125f,
                                .outlineColor = {0.25f, 0.0f, 0.5f}, .outlineLightingMix = 0.25f,
                                .matcapFactor = {0.5f, 1.0f, 0.25f}, .shadingShiftTextureScale = 0.5f};
  decal.matcapImage = 1;
  decal.shadingShiftImage = 1;  // MToon's masks
  decal.rimMultiplyImage = 0;
  decal.outlineWidthImage = 1;
  decal.outlineWidthSampling.magFilter = eng::TextureFilter::Nearest;
  decal.matcapSampling.wrapS = eng::TextureWrap::ClampToEdge;
  model.materials.push_back(decal);

  eng::Mesh face;
  face.name = "Face";
  face.targetNames = {"smile", "blink", "still"};
  face.defaultWeights = {0.0f, 0.25f, 1.0f};
  for (int p = 0; p < 2; ++p) {
    eng::Primitive prim;
    const int n = 40 + p * 10;
    for (int v = 0; v < n; ++v) {
      prim.positions.push_back({v * 0.1f, (v % 7) * 0.3f, p * 1.0f});
      prim.normals.push_back(glm::normalize(glm::vec3(0.1f * v, 1.0f, 0.5f)));
      prim.texcoords.push_back({v / float(n), 1.0f - v / float(n)});
      prim.tangents.push_back({1, 0, 0, v % 2 ? 1.0f : -1.0f});
      if (p == 0) prim.colors.push_back({v / float(n), 0.5f, 1.0f - v / float(n), v % 2 ? 1.0f : 0.75f});
    }
    for (int v = 0; v + 2 < n; v += 3) prim.indices.insert(prim.indices.end(), {uint32_t(v), uint32_t(v + 1), uint32_t(v + 2)});
    prim.material = p;
    eng::MorphTarget smile;  // moves every vertex: dense
    eng::MorphTarget blink;  // moves two vertices: sparse
    eng::MorphTarget still;  // positions present but all zero
    smile.positions.resize(n);
    smile.normals.resize(n);
    for (int v = 0; v < n; ++v) {
      smile.positions[v] = {0.01f * v, -0.02f, 0.003f * (v % 5)};
      smile.normals[v] = {0.0f, 0.01f * (v % 3), 0.0f};
    }
    blink.positions.assign(n, glm::vec3(0.0f));
    blink.positions[3] = {0, -0.5f, 0};
    blink.positions[n - 1] = {0.25f, 0, 0};
    blink.tangents.assign(n, glm::vec3(0.0f));
    blink.tangents[5] = {0, 0.1f, 0};
    still.positions.assign(n, glm::vec3(0.0f));
    prim.targets = {smile, blink, still};
    face.primitives.push_back(std::move(prim));
  }
  model.meshes.push_back(face);

  eng::Mesh eye;
  eye.name = "Eye";
  eye.primitives.push_back(eng::Primitive{.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                          .normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}},
                                          .indices = {0, 1, 2}});
  model.meshes.push_back(eye);

  eng::Node root;
  root.name = "root";
  root.hasMatrix = true;
  root.matrix = glm::mat4(2.0f);
  root.matrix[3] = glm::vec4(1, 2, 3, 1);
  root.children = {1, 2};
  eng::Node head;
  head.name = "head";
  head.parent = 0;
  head.mesh = 0;
  head.translation = {0, 1.5f, 0};
  head.rotation = glm::normalize(glm::quat(0.9f, 0.1f, 0.2f, 0.3f));
  head.scale = {1, 1, 1.5f};
  eng::Node eyeNode;
  eyeNode.name = "eye";
  eyeNode.parent = 0;
  eyeNode.mesh = 1;
  model.nodes = {root, head, eyeNode};
  model.roots = {0};

  eng::Animation anim;
  anim.name = "talk";
  const eng::Interpolation kinds[] = {eng::Interpolation::Linear, eng::Interpolation::Step,
                                      eng::Interpolation::CubicSpline};
  for (eng::Interpolation kind : kinds) {
    eng::WeightsChannel ch;
    ch.node = 1;
    ch.mesh = 0;
    ch.interpolation = kind;
    ch.targetCount = 3;
    ch.times = {0.0f, 0.5f, 1.25f};
    const size_t perKey = kind == eng::Interpolation::CubicSpline ? 9 : 3;
    for (size_t i = 0; i < ch.times.size() * perKey; ++i) ch.values.push_back(0.1f * static_cast<float>(i % 11));
    anim.channels.push_back(ch);
  }
  model.animations.push_back(anim);
  model.calibration = {{"AU1_InnerBrowRaiser", 0.79f}, {"AU26_JawDrop", 1.69f}};  // as facial autorig states
  return model;
}

void expectSameModel(const eng::Model& a, const eng::Model& b) {
  EXPECT_EQ(a.calibration, b.calibration);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    const eng::Mesh& x = a.meshes[m];
    const eng::Mesh& y = b.meshes[m];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.targetNames, y.targetNames);
    EXPECT_EQ(x.defaultWeights, y.defaultWeights);
    ASSERT_EQ(x.primitives.size(), y.primitives.size());
    for (size_t p = 0; p < x.primitives.size(); ++p) {
      const eng::Primitive& P = x.primitives[p];
      const eng::Primitive& Q = y.primitives[p];
      EXPECT_EQ(P.positions, Q.positions) << "mesh " << m << " primitive " << p;
      EXPECT_EQ(P.normals, Q.normals);
      EXPECT_EQ(P.texcoords, Q.texcoords);
      EXPECT_EQ(P.tangents, Q.tangents);
      EXPECT_EQ(P.colors, Q.colors);
      EXPECT_EQ(P.indices, Q.indices);
      EXPECT_EQ(P.material, Q.material);
      ASSERT_EQ(P.targets.size(), Q.targets.size());
      for (size_t t = 0; t < P.targets.size(); ++t) {
        EXPECT_EQ(P.targets[t].positions, Q.targets[t].positions) << "target " << t;
        EXPECT_EQ(P.targets[t].normals, Q.targets[t].normals) << "target " << t;
        EXPECT_EQ(P.targets[t].tangents, Q.targets[t].tangents) << "target " << t;
      }
    }
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const eng::Material& x = a.materials[i];
    const eng::Material& y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.baseColorFactor, y.baseColorFactor);
    EXPECT_EQ(x.emissiveFactor, y.emissiveFactor);
    EXPECT_EQ(x.baseColorImage, y.baseColorImage);
    EXPECT_EQ(x.metallicRoughnessImage, y.metallicRoughnessImage);
    EXPECT_EQ(x.metallicRoughnessSampling, y.metallicRoughnessSampling) << x.name;
    EXPECT_EQ(x.normalImage, y.normalImage);
    EXPECT_EQ(x.normalSampling, y.normalSampling) << x.name;
    EXPECT_EQ(x.normalScale, y.normalScale);
    EXPECT_EQ(x.occlusionImage, y.occlusionImage);
    EXPECT_EQ(x.occlusionSampling, y.occlusionSampling) << x.name;
    EXPECT_EQ(x.occlusionStrength, y.occlusionStrength);
    EXPECT_EQ(x.emissiveImage, y.emissiveImage);
    EXPECT_EQ(x.emissiveSampling, y.emissiveSampling) << x.name;
    for (const eng::MaterialTexture& slot : eng::kMaterialTextures) {
      EXPECT_EQ(x.*slot.image, y.*slot.image) << x.name << " " << slot.name;
      EXPECT_EQ(x.*slot.sampling, y.*slot.sampling) << x.name << " " << slot.name;
    }
    EXPECT_EQ(x.roughness, y.roughness);
    EXPECT_EQ(x.metallic, y.metallic);
    EXPECT_EQ(x.doubleSided, y.doubleSided);
    EXPECT_EQ(x.alphaMode, y.alphaMode);
    EXPECT_EQ(x.alphaCutoff, y.alphaCutoff);
    EXPECT_EQ(x.unlit, y.unlit);
    EXPECT_EQ(x.toon.has_value(), y.toon.has_value()) << x.name;
    if (x.toon && y.toon) {
      EXPECT_TRUE(*x.toon == *y.toon) << x.name << ": MToon values differ after the round trip";
    }
    EXPECT_EQ(x.baseColorSampling, y.baseColorSampling) << x.name << ": " << eng::describeSampling(y.baseColorSampling);
    ASSERT_EQ(x.detailLayers.size(), y.detailLayers.size());
    for (size_t l = 0; l < x.detailLayers.size(); ++l) {
      EXPECT_EQ(x.detailLayers[l].image, y.detailLayers[l].image);
      EXPECT_EQ(x.detailLayers[l].target, y.detailLayers[l].target);
      EXPECT_EQ(x.detailLayers[l].strength, y.detailLayers[l].strength);
      EXPECT_EQ(x.detailLayers[l].blend, y.detailLayers[l].blend);
    }
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].width, b.images[i].width);
    EXPECT_EQ(a.images[i].height, b.images[i].height);
    EXPECT_EQ(a.images[i].rgba8, b.images[i].rgba8);
  }
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const eng::Node& x = a.nodes[i];
    const eng::Node& y = b.nodes[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.children, y.children);
    EXPECT_EQ(x.mesh, y.mesh);
    EXPECT_EQ(x.hasMatrix, y.hasMatrix);
    EXPECT_EQ(x.localTransform(), y.localTransform()) << "node " << i;
  }
  EXPECT_EQ(a.roots, b.roots);
  ASSERT_EQ(a.animations.size(), b.animations.size());
  for (size_t i = 0; i < a.animations.size(); ++i) {
    EXPECT_EQ(a.animations[i].name, b.animations[i].name);
    ASSERT_EQ(a.animations[i].channels.size(), b.animations[i].channels.size());
    for (size_t c = 0; c < a.animations[i].channels.size(); ++c) {
      const eng::WeightsChannel& x = a.animations[i].channels[c];
      const eng::WeightsChannel& y = b.animations[i].channels[c];
      EXPECT_EQ(x.node, y.node);
      EXPECT_EQ(x.mesh, y.mesh);
      EXPECT_EQ(x.interpolation, y.interpolation);
      EXPECT_EQ(x.targetCount, y.targetCount);
      EXPECT_EQ(x.times, y.times);
      EXPECT_EQ(x.values, y.values);
    }
  }
}

Json glbJson(const std::filesystem::path& path) {
  const std::string bytes = scene_test::readText(path);
  uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, bytes.data() + 12, 4);
  return Json::parse(bytes.substr(20, jsonLength));
}

eng::Model reload(const std::filesystem::path& path) {
  auto model = eng::loadModel(path);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  if (!model.ok()) return {};
  EXPECT_TRUE(model->warnings.empty()) << model->warnings.front();
  return std::move(*model);
}

TEST(GltfWriter, GlbRoundTripReproducesTheModel) {
  const auto dir = freshTempDir("writer_glb");
  const eng::Model model = richModel();
  auto saved = eng::saveModel(model, dir / "rich.glb");
  ASSERT_TRUE(saved.ok()) << saved.error().message;
  expectSameModel(model, reload(dir / "rich.glb"));
}

TEST(GltfWriter, GltfWithBinSidecarRoundTripReproducesTheModel) {
  const auto dir = freshTempDir("writer_gltf");
  const eng::Model model = richModel();
  ASSERT_TRUE(eng::saveModel(model, dir / "rich face.gltf").ok());
  EXPECT_TRUE(std::filesystem::exists(dir / "rich face.bin"));
  EXPECT_NE(scene_test::readText(dir / "rich face.gltf").find("rich%20face.bin"), std::string::npos);
  expectSameModel(model, reload(dir / "rich face.gltf"));
}

TEST(GltfWriter, TargetsMovingFewVerticesAreSparseAndStillTargetsHaveNoData) {
  const auto dir = freshTempDir("writer_sparse");
  ASSERT_TRUE(eng::saveModel(richModel(), dir / "rich.glb").ok());
  const Json doc = glbJson(dir / "rich.glb");
  const Json& targets = doc["meshes"][0]["primitives"][0]["targets"];
  ASSERT_EQ(targets.size(), 3u);
  const Json& smile = doc["accessors"][targets[0]["POSITION"].get<int>()];
  const Json& blink = doc["accessors"][targets[1]["POSITION"].get<int>()];
  const Json& still = doc["accessors"][targets[2]["POSITION"].get<int>()];
  EXPECT_TRUE(smile.contains("bufferView"));
  EXPECT_FALSE(smile.contains("sparse"));
  EXPECT_FALSE(blink.contains("bufferView")) << "sparse over an implicit zero base";
  ASSERT_TRUE(blink.contains("sparse"));
  EXPECT_EQ(blink["sparse"]["count"], 2);
  EXPECT_EQ(blink["count"], 40);
  EXPECT_EQ(blink["min"], Json({0.0, -0.5, 0.0}));
  EXPECT_FALSE(still.contains("bufferView"));
  EXPECT_FALSE(still.contains("sparse"));
  EXPECT_EQ(doc["meshes"][0]["extras"]["targetNames"], Json({"smile", "blink", "still"}));
  EXPECT_EQ(doc["meshes"][0]["weights"], Json({0.0, 0.25, 1.0}));
  EXPECT_EQ(doc["materials"][0]["extras"]["detailLayers"][0]["target"], "smile");
  EXPECT_EQ(doc["images"][0]["mimeType"], "image/png");
}

TEST(GltfWriter, TwoHundredFiftySixTargetsRoundTrip) {
  const auto dir = freshTempDir("writer_256");
  eng::Model model;
  eng::Mesh mesh;
  mesh.name = "Grid";
  eng::Primitive prim;
  const int side = 32;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      prim.positions.push_back({x * 0.1f, y * 0.1f, 0.0f});
      prim.normals.push_back({0, 0, 1});
    }
  for (int y = 0; y + 1 < side; ++y)
    for (int x = 0; x + 1 < side; ++x) {
      const uint32_t i = y * side + x;
      prim.indices.insert(prim.indices.end(), {i, i + 1, i + side, i + 1, i + side + 1, i + side});
    }
  for (int t = 0; t < 256; ++t) {
    eng::MorphTarget target;
    target.positions.assign(prim.positions.size(), glm::vec3(0.0f));
    // Every 4th target moves everything (dense), the rest move a few vertices (sparse).
    if (t % 4 == 0)
      for (size_t v = 0; v < target.positions.size(); ++v) target.positions[v] = {0, 0, 0.001f * (t + 1) * (v % 3 + 1)};
    else
      for (int k = 0; k < 5; ++k) target.positions[(t * 7 + k * 131) % target.positions.size()] = {0, 0, 0.01f * t};
    prim.targets.push_back(std::move(target));
    mesh.targetNames.push_back("shape_" + std::to_string(t));
    mesh.defaultWeights.push_back(t == 255 ? 1.0f : 0.0f);
  }
  mesh.primitives.push_back(std::move(prim));
  model.meshes.push_back(std::move(mesh));
  model.nodes.push_back(eng::Node{.name = "grid", .mesh = 0});
  model.roots = {0};
  ASSERT_TRUE(eng::saveModel(model, dir / "grid256.glb").ok());
  const eng::Model loaded = reload(dir / "grid256.glb");
  expectSameModel(model, loaded);
  const eng::WeightLayout layout(loaded);
  EXPECT_EQ(layout.total(), 256u);
  EXPECT_EQ(layout.names()[255], "shape_255");
  EXPECT_EQ(layout.defaults()[255], 1.0f);
  const Json doc = glbJson(dir / "grid256.glb");
  int sparse = 0;
  for (const Json& acc : doc["accessors"]) sparse += acc.contains("sparse");
  EXPECT_EQ(sparse, 192);
}

TEST(GltfWriter, SharedAssetsRoundTrip) {
  FACIAL_REQUIRE_SHARED();
  const auto dir = freshTempDir("writer_shared");
  for (const char* file : {"facecap.glb", "khronos/MorphStressTest/MorphStressTest.gltf"}) {
    auto original = eng::loadModel(testing_support::sharedDir() / "assets" / file);
    ASSERT_TRUE(original.ok()) << original.error().message;
    // Animations without weights channels (bone-only clips) have nothing the writer keeps.
    std::erase_if(original->animations, [](const eng::Animation& a) { return a.channels.empty(); });
    ASSERT_TRUE(eng::saveModel(*original, dir / "copy.glb").ok());
    expectSameModel(*original, reload(dir / "copy.glb"));
  }
}

TEST(GltfWriter, RefusesAnInconsistentModelNamingTheProblem) {
  const auto dir = freshTempDir("writer_invalid");
  eng::Model model = richModel();
  model.meshes[0].primitives[1].normals.pop_back();
  auto saved = eng::saveModel(model, dir / "bad.glb");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("mesh 0 'Face' primitive 1 has 49 normals for 50 vertices"), std::string::npos)
      << saved.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));

  model = richModel();
  model.meshes[0].primitives[0].targets[1].positions.resize(3);
  saved = eng::saveModel(model, dir / "bad.glb");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("target 1 has 3 position deltas for 40 vertices"), std::string::npos)
      << saved.error().message;

  model = richModel();
  model.meshes[0].defaultWeights.pop_back();
  saved = eng::saveModel(model, dir / "bad.glb");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("2 default weights for 3 targets"), std::string::npos) << saved.error().message;
}

TEST(GltfWriter, RefusesAnUnknownExtensionAndAnUnwritablePath) {
  const auto dir = freshTempDir("writer_paths");
  auto saved = eng::saveModel(richModel(), dir / "face.obj");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("unknown extension '.obj'"), std::string::npos);
  saved = eng::saveModel(richModel(), dir / "no" / "such" / "dir" / "face.glb");
  ASSERT_FALSE(saved.ok());
  EXPECT_NE(saved.error().message.find("cannot open for writing"), std::string::npos) << saved.error().message;
}

}  // namespace
