// Offscreen rendering of procedural models: background, shading, instancing,
// culling, default material, and bad input.
#include "engine/vk/draw/offscreen_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/component_wise.hpp>
#include <gtest/gtest.h>

#include "engine/scene/weights.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

using vk_test::pixel;
using vk_test::viewOf;

eng::Image renderOrFail(const eng::vk::SceneView& view, std::span<const eng::vk::ModelInstance> instances) {
  auto image = vk_test::renderer().render(view, instances);
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  return image ? std::move(image).value() : eng::Image{};
}

TEST(OffscreenRender, EmptySceneIsTheBackgroundGradient) {
  const eng::Image image = renderOrFail(viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}}), {});
  ASSERT_EQ(image.width, 256);
  ASSERT_EQ(image.height, 256);
  const glm::ivec4 top = pixel(image, 128, 2);
  const glm::ivec4 bottom = pixel(image, 128, 253);
  EXPECT_GT(top.g, bottom.g + 40) << "lighter at the top";
  EXPECT_EQ(top.a, 255);
  // Neutral: no strong colour cast.
  EXPECT_LT(std::abs(top.r - top.b), 20);
}

TEST(OffscreenRender, SphereCoversTheCentreAndIsLitFromTheKeySide) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  const eng::Image background = renderOrFail(viewOf(model.bounds()), {});
  const eng::Image image = renderOrFail(viewOf(model.bounds()), {&instance, 1});
  const double coverage = vk_test::coverageAgainst(image, background);
  EXPECT_GT(coverage, 0.3) << "the framed sphere fills much of the image";
  EXPECT_LT(coverage, 0.9);
  const glm::ivec4 centre = pixel(image, 128, 128);
  EXPECT_GT(centre.r, centre.b) << "warm base colour";
  // Key light from the camera's upper left: that side is brighter than the lower right.
  const glm::ivec4 upperLeft = pixel(image, 90, 90);
  const glm::ivec4 lowerRight = pixel(image, 166, 166);
  EXPECT_GT(upperLeft.r + upperLeft.g + upperLeft.b, lowerRight.r + lowerRight.g + lowerRight.b + 30);
}

TEST(OffscreenRender, InstancesOfOneMeshDrawInOneCallWithTheirOwnWeights) {
  testing_support::SphereSpec spec;
  spec.targets = 2;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> rest{0.0f, 0.0f};
  const std::vector<float> bulged{1.0f, 0.0f};
  const std::vector<eng::vk::ModelInstance> instances{
      {&*gpu, glm::translate(glm::mat4(1.0f), {-2.5f, 0, 0}), rest},
      {&*gpu, glm::mat4(1.0f), bulged},
      {&*gpu, glm::translate(glm::mat4(1.0f), {2.5f, 0, 0}), rest},
  };
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-3.6f, -1.3f, -1.3f}, {3.6f, 1.3f, 1.3f}});
  const eng::Image image = renderOrFail(view, instances);
  const eng::vk::FrameStats stats = vk_test::renderer().lastFrameStats();
  EXPECT_EQ(stats.draws, 1u) << "one primitive: one instanced draw for all three instances";
  EXPECT_EQ(stats.instances, 3u);
  EXPECT_EQ(stats.activeWeights, 1u) << "only the one non-zero weight is uploaded";

  const eng::Image background = renderOrFail(view, {});
  // Each instance covers its own third of the image.
  for (int x : {40, 128, 216}) {
    const glm::ivec4 p = pixel(image, x, 128), b = pixel(background, x, 128);
    EXPECT_GT(std::abs(p.r - b.r) + std::abs(p.g - b.g), 30) << "instance at column " << x;
  }
  // Rendering the middle instance at rest changes only its pixels.
  std::vector<eng::vk::ModelInstance> allRest = instances;
  allRest[1].weights = rest;
  const eng::Image restImage = renderOrFail(view, allRest);
  size_t changedLeft = 0, changedMiddle = 0, changedRight = 0;
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      if (pixel(image, x, y) == pixel(restImage, x, y)) continue;
      ++(x < 85 ? changedLeft : x > 185 ? changedRight : changedMiddle);
    }
  }
  EXPECT_EQ(changedLeft, 0u);
  EXPECT_EQ(changedRight, 0u);
  EXPECT_GT(changedMiddle, 50u) << "the bulge of target t0 shows on the middle instance only";
}

TEST(OffscreenRender, BackFacesCulledUnlessDoubleSided) {
  // A sphere seen from inside shows only back faces.
  for (bool doubleSided : {false, true}) {
    testing_support::SphereSpec spec;
    spec.targets = 0;
    spec.doubleSided = doubleSided;
    spec.radius = 10.0f;
    const eng::Model model = testing_support::makeSphereModel(spec);
    auto gpu = vk_test::renderer().upload(model);
    ASSERT_TRUE(gpu) << gpu.error().message;
    eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});  // camera inside the sphere
    view.camera.sceneRadius = 20.0f;  // clip planes that reach the sphere around the camera
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    const eng::Image background = renderOrFail(view, {});
    const eng::Image image = renderOrFail(view, {&instance, 1});
    const double coverage = vk_test::coverageAgainst(image, background);
    if (doubleSided)
      EXPECT_GT(coverage, 0.95) << "double-sided: the inside is drawn";
    else
      EXPECT_EQ(coverage, 0.0) << "single-sided: back faces culled";
  }
}

// A sphere without targets, uploaded (the spec's targets are ignored).
eng::Result<eng::vk::GpuModel> uploadPlainSphere(testing_support::SphereSpec spec) {
  spec.targets = 0;
  return vk_test::renderer().upload(testing_support::makeSphereModel(spec));
}

// Mean absolute difference of the colour channels, in 8-bit levels.
double meanDifference(const eng::Image& a, const eng::Image& b) {
  if (a.width != b.width || a.height != b.height) return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const glm::ivec4 d = glm::abs(pixel(a, x, y) - pixel(b, x, y));
      sum += d.r + d.g + d.b;
    }
  return sum / (3.0 * a.width * a.height);
}

TEST(OffscreenRender, MirroredTransformStillShowsTheOutside) {
  // glTF: a negative determinant turns the winding, so front faces wind
  // clockwise. A sphere is its own mirror image: scaled by -1 in x it must
  // look the same, not show its inside (the far half's back faces).
  for (bool doubleSided : {false, true}) {
    auto gpu = uploadPlainSphere({.doubleSided = doubleSided});
    ASSERT_TRUE(gpu) << gpu.error().message;
    const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
    const eng::vk::ModelInstance plain{&*gpu, glm::mat4(1.0f), {}};
    const eng::vk::ModelInstance mirrored{&*gpu, glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)), {}};
    const eng::Image expected = renderOrFail(view, {&plain, 1});
    const eng::Image image = renderOrFail(view, {&mirrored, 1});
    EXPECT_LT(meanDifference(image, expected), 1.0) << (doubleSided ? "double-sided" : "single-sided")
                                                    << ": the mirrored sphere is lit like the plain one";
    EXPECT_NEAR(pixel(image, 128, 128).g, pixel(expected, 128, 128).g, 4) << "centre of the sphere";
  }
}

TEST(OffscreenRender, MirroredAndPlainInstancesDrawnTogether) {
  // Two instances of one model, one mirrored: two draws that wind
  // differently, each showing its outside.
  auto gpu = uploadPlainSphere({});
  ASSERT_TRUE(gpu) << gpu.error().message;
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-3, -1, -1}, {3, 1, 1}});
  const glm::mat4 left = glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, 0.0f, 0.0f));
  const glm::mat4 right = glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.0f, 0.0f));
  const glm::mat4 flip = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  const std::vector<eng::vk::ModelInstance> plain{{&*gpu, left, {}}, {&*gpu, right, {}}};
  const std::vector<eng::vk::ModelInstance> mixed{{&*gpu, left * flip, {}}, {&*gpu, right, {}}};
  const eng::Image expected = renderOrFail(view, plain);
  const eng::Image image = renderOrFail(view, mixed);
  EXPECT_LT(meanDifference(image, expected), 1.0);
}

TEST(OffscreenRender, AlphaModesFollowGltf) {
  // A sphere whose base colour has alpha 0.3: OPAQUE ignores it, MASK with a
  // cutoff above it cuts everything away and below it keeps everything,
  // BLEND lets the backdrop show through.
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  const eng::Image background = renderOrFail(view, {});
  auto render = [&](eng::AlphaMode mode, float cutoff) {
    auto gpu = uploadPlainSphere({.color = {0.9f, 0.2f, 0.1f, 0.3f}, .alphaMode = mode, .alphaCutoff = cutoff});
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const eng::Image opaque = render(eng::AlphaMode::Opaque, 0.5f);
  EXPECT_GT(vk_test::coverageAgainst(opaque, background), 0.3);
  EXPECT_EQ(vk_test::coverageAgainst(render(eng::AlphaMode::Mask, 0.5f), background), 0.0) << "alpha 0.3 < cutoff 0.5";
  EXPECT_LT(meanDifference(render(eng::AlphaMode::Mask, 0.2f), opaque), 0.5) << "alpha 0.3 >= cutoff 0.2: as opaque";
  const eng::Image blended = render(eng::AlphaMode::Blend, 0.5f);
  const glm::ivec4 o = pixel(opaque, 128, 128), b = pixel(blended, 128, 128), g = pixel(background, 128, 128);
  // Red: 0.3 of the way from the backdrop toward the opaque sphere (in the
  // tone-mapped output; blending is in linear light, so only roughly).
  EXPECT_GT(b.r, g.r + 0.1 * (o.r - g.r)) << "the sphere shows";
  EXPECT_LT(b.r, g.r + 0.6 * (o.r - g.r)) << "the backdrop shows through";
}

TEST(OffscreenRender, MaskedSurfacesCastShadowsOnlyWhereTheyAreDrawn) {
  // A sphere cut away entirely (alpha below its cutoff) between the key
  // light and a big opaque sphere: the scene must look as if it were not
  // there, shadow included.
  auto cutGpu = uploadPlainSphere({.color = {0.1f, 0.9f, 0.1f, 0.3f}, .alphaMode = eng::AlphaMode::Mask});
  auto wallGpu = uploadPlainSphere({.radius = 2.0f});
  ASSERT_TRUE(cutGpu && wallGpu);
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-2, -2, -2}, {2, 2, 2}});
  const glm::mat4 inFront = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.6f));
  const std::vector<eng::vk::ModelInstance> both{{&*wallGpu, glm::mat4(1.0f), {}}, {&*cutGpu, inFront, {}}};
  const std::vector<eng::vk::ModelInstance> wallOnly{{&*wallGpu, glm::mat4(1.0f), {}}};
  EXPECT_LT(meanDifference(renderOrFail(view, both), renderOrFail(view, wallOnly)), 0.05);
}

TEST(OffscreenRender, BlendedDrawsComeAfterOpaqueOnes) {
  // A half-transparent sphere in front of an opaque one, listed first: the
  // opaque sphere must still show through it (blended draws are drawn last,
  // and write no depth).
  auto frontGpu = uploadPlainSphere({.color = {0.1f, 0.2f, 0.9f, 0.4f}, .alphaMode = eng::AlphaMode::Blend});
  auto backGpu = uploadPlainSphere({.color = {0.9f, 0.8f, 0.1f, 1.0f}});
  ASSERT_TRUE(frontGpu && backGpu);
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1.5f, -1.5f, -1.5f}, {1.5f, 1.5f, 1.5f}});
  const glm::mat4 nearer = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 1.5f));
  const glm::mat4 farther = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -1.5f));
  const std::vector<eng::vk::ModelInstance> blendFirst{{&*frontGpu, nearer, {}}, {&*backGpu, farther, {}}};
  const std::vector<eng::vk::ModelInstance> onlyFront{{&*frontGpu, nearer, {}}};
  const glm::ivec4 both = pixel(renderOrFail(view, blendFirst), 128, 128);
  const glm::ivec4 alone = pixel(renderOrFail(view, onlyFront), 128, 128);
  EXPECT_GT(both.r, alone.r + 20) << "the yellow sphere behind shows through the blue one";
}

// A square facing the camera whose u runs from -1 to 2 across it, textured
// with two texels: red on the left half of the texture, green on the right.
eng::Model twoTexelSquare(const eng::TextureSampling& sampling) {
  eng::Model model;
  model.sourcePath = "<two-texel square>";
  eng::Primitive& prim = model.meshes.emplace_back().primitives.emplace_back();
  prim.positions = {{-1.5f, -0.5f, 0.0f}, {1.5f, -0.5f, 0.0f}, {1.5f, 0.5f, 0.0f}, {-1.5f, 0.5f, 0.0f}};
  prim.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  prim.texcoords = {{-1.0f, 0.5f}, {2.0f, 0.5f}, {2.0f, 0.5f}, {-1.0f, 0.5f}};
  prim.indices = {0, 1, 2, 0, 2, 3};
  prim.material = 0;
  model.images.push_back({"red|green", 2, 1, {255, 0, 0, 255, 0, 255, 0, 255}});
  eng::Material& mat = model.materials.emplace_back();
  mat.baseColorImage = 0;
  mat.baseColorSampling = sampling;
  model.nodes.emplace_back().mesh = 0;
  model.roots.push_back(0);
  return model;
}

TEST(OffscreenRender, BaseColourFollowsTheSamplersWrapModes) {
  // Six columns across the square, at u = -0.75, -0.25, ..., 1.75.
  auto columns = [](eng::TextureWrap wrap) {
    eng::TextureSampling sampling{wrap, wrap, eng::TextureFilter::Nearest, eng::TextureFilter::Nearest, false};
    const eng::Model model = twoTexelSquare(sampling);
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    if (!gpu) return std::string();
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    const eng::Image image = renderOrFail(viewOf(model.bounds()), {&instance, 1});
    const eng::Image background = renderOrFail(viewOf(model.bounds()), {});
    // The square's columns, found from where it covers the backdrop on the middle row.
    int left = image.width, right = -1;
    for (int x = 0; x < image.width; ++x)
      if (glm::any(glm::greaterThan(glm::abs(pixel(image, x, image.height / 2) - pixel(background, x, image.height / 2)),
                                    glm::ivec4(12)))) {
        left = std::min(left, x);
        right = std::max(right, x);
      }
    std::string out;
    for (int c = 0; c < 6; ++c) {
      const glm::ivec4 p = pixel(image, left + (right - left) * (2 * c + 1) / 12, image.height / 2);
      out += p.r > p.g + 30 ? 'R' : p.g > p.r + 30 ? 'G' : '?';
    }
    return out;
  };
  EXPECT_EQ(columns(eng::TextureWrap::Repeat), "RGRGRG");
  EXPECT_EQ(columns(eng::TextureWrap::ClampToEdge), "RRRGGG");
  EXPECT_EQ(columns(eng::TextureWrap::MirroredRepeat), "GRRGGR");
}

// glTF's metallicRoughnessTexture scales the factors: a material whose
// factor says metal (1) but whose texture says none (blue 0) is drawn as the
// same material with metallic 0, where it came out near black (a rough metal
// under the studio lights: Ready Player Me's trousers and glasses).
TEST(OffscreenRender, MetallicRoughnessTextureScalesTheFactors) {
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](float metallic, int blue) {
    eng::Model model = testing_support::makeSphereModel({.targets = 0});
    eng::Material& mat = model.materials.at(0);
    mat.metallic = metallic;
    mat.roughness = 1.0f;
    if (blue >= 0) {
      model.images.push_back({"metal", 1, 1, {0, 255, uint8_t(blue), 255}});
      mat.metallicRoughnessImage = 0;
    }
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const eng::Image dielectric = render(0.0f, -1), metal = render(1.0f, -1);
  const eng::Image metalTextureSaysNone = render(1.0f, 0), metalTextureSaysMetal = render(1.0f, 255);
  const double apart = meanDifference(dielectric, metal);
  std::printf("mean difference from the dielectric: metal factor %.2f, the texture saying none %.2f, saying metal %.2f\n",
              apart, meanDifference(dielectric, metalTextureSaysNone), meanDifference(dielectric, metalTextureSaysMetal));
  EXPECT_GT(apart, 5.0) << "a rough metal and a dielectric look apart";
  EXPECT_LT(meanDifference(dielectric, metalTextureSaysNone), 0.05);
  EXPECT_LT(meanDifference(metal, metalTextureSaysMetal), 0.05);
}

// A metal's colour is what it reflects: under the studio rig, which has no
// environment map, a gold metal was black wherever no light's highlight fell
// on it (Ready Player Me's belt buckle and glasses frames, gold in three.js).
// It now reflects the ambient hemisphere at full strength, and the lights'
// highlights at a metal's strength rather than skin's gentle one.
TEST(OffscreenRender, AMetalShowsItsColourAwayFromTheHighlights) {
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  const eng::Image background = renderOrFail(view, {});
  const glm::vec4 gold{1.0f, 0.77f, 0.34f, 1.0f};
  // The sphere's mean colour over the pixels it covers, and its darkest tenth's mean brightness.
  auto render = [&](float metallic) {
    eng::Model model = testing_support::makeSphereModel({.targets = 0});
    eng::Material& mat = model.materials.at(0);
    mat.baseColorFactor = gold;
    mat.metallic = metallic;
    mat.roughness = 0.4f;
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    const eng::Image image = renderOrFail(view, {&instance, 1});
    glm::dvec3 sum(0.0);
    std::vector<int> brightness;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const glm::ivec4 p = pixel(image, x, y), b = pixel(background, x, y);
        if (!glm::any(glm::greaterThan(glm::abs(p - b), glm::ivec4(12)))) continue;
        sum += glm::dvec3(p.r, p.g, p.b);
        brightness.push_back(p.r + p.g + p.b);
      }
    std::sort(brightness.begin(), brightness.end());
    double dark = 0.0;
    const size_t tenth = std::max<size_t>(brightness.size() / 10, 1);
    for (size_t i = 0; i < tenth && i < brightness.size(); ++i) dark += brightness[i] / 3.0;
    const glm::dvec3 mean = brightness.empty() ? glm::dvec3(0.0) : sum / double(brightness.size());
    return std::pair{mean, dark / double(tenth)};
  };
  const auto [dielectric, dielectricDark] = render(0.0f);
  const auto [metal, metalDark] = render(1.0f);
  std::printf("mean RGB: dielectric %.0f %.0f %.0f, metal %.0f %.0f %.0f; darkest tenth: %.0f, %.0f\n", dielectric.r,
              dielectric.g, dielectric.b, metal.r, metal.g, metal.b, dielectricDark, metalDark);
  // Measured 0.31 of the dielectric's red and a darkest tenth of 2 before the ambient reflection; 0.44
  // and 28 with it, 0.52 and 31 with the metal's GGX lobe.
  EXPECT_GT(metal.r, 0.37 * dielectric.r) << "the metal is not much darker than a painted surface of its colour";
  EXPECT_GT(metal.r, metal.b + 20.0) << "and as gold";
  EXPECT_GT(metalDark, 12.0) << "no part of it is black";
}

// A square facing the camera with its texture upright on it (v runs down the
// square, as glTF's image rows do), normals `normal`, and a one-texel normal
// texture `texel` (none when x < 0): with glTF vertex tangents along +u, or
// without, when the renderer derives the frame from the screen.
eng::Model normalMappedSquare(glm::vec3 normal, glm::ivec3 texel, bool tangents) {
  eng::Model model;
  model.sourcePath = "<normal-mapped square>";
  eng::Primitive& prim = model.meshes.emplace_back().primitives.emplace_back();
  prim.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {-1.0f, 1.0f, 0.0f}};
  prim.normals.assign(4, glm::normalize(normal));
  prim.texcoords = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  if (tangents) prim.tangents.assign(4, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  prim.indices = {0, 1, 2, 0, 2, 3};
  prim.material = 0;
  eng::Material& mat = model.materials.emplace_back();
  mat.baseColorFactor = {0.8f, 0.6f, 0.5f, 1.0f};
  if (texel.x >= 0) {
    model.images.push_back({"normal", 1, 1, {uint8_t(texel.x), uint8_t(texel.y), uint8_t(texel.z), 255}});
    mat.normalImage = 0;
  }
  model.nodes.emplace_back().mesh = 0;
  model.roots.push_back(0);
  return model;
}

// glTF's normal texture: +X toward +u, +Y up the image, through the vertex
// tangents or, without them, a frame from the screen derivatives. A texel
// tilted 45 degrees up (or right) must light the square as normals tilted so
// would, whichever frame; tilted the wrong way it would match the opposite
// tilt, which the key light from the upper left tells apart.
TEST(OffscreenRender, NormalTextureBendsTheNormalsAsGltfOrientsIt) {
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -0.2f}, {1, 1, 0.2f}});
  auto render = [&](const eng::Model& model) {
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    if (!gpu) return eng::Image{};
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const glm::vec3 front(0.0f, 0.0f, 1.0f);
  const struct {
    const char* name;
    glm::vec3 normal;
    glm::ivec3 texel;
  } tilts[] = {{"up", {0.0f, 1.0f, 1.0f}, {128, 218, 218}}, {"right", {1.0f, 0.0f, 1.0f}, {218, 128, 218}}};
  for (const auto& tilt : tilts) {
    const eng::Image tilted = render(normalMappedSquare(tilt.normal, {-1, 0, 0}, false));
    const eng::Image opposite = render(normalMappedSquare(glm::vec3(-tilt.normal.x, -tilt.normal.y, 1.0f), {-1, 0, 0}, false));
    ASSERT_GT(meanDifference(tilted, opposite), 5.0) << tilt.name << ": the key light tells the tilts apart";
    for (const bool tangents : {true, false}) {
      const eng::Image mapped = render(normalMappedSquare(front, tilt.texel, tangents));
      const double off = meanDifference(mapped, tilted);
      std::printf("tilted %s by the texture, %s: %.2f levels from normals so tilted, %.2f from the opposite tilt\n",
                  tilt.name, tangents ? "vertex tangents" : "derived frame", off, meanDifference(mapped, opposite));
      EXPECT_LT(off, 1.0) << tilt.name << (tangents ? ", vertex tangents" : ", derived frame");
    }
  }
  // A flat texel changes nothing; a scale of 0 flattens a tilted one.
  const eng::Image plain = render(normalMappedSquare(front, {-1, 0, 0}, false));
  EXPECT_LT(meanDifference(render(normalMappedSquare(front, {128, 128, 255}, false)), plain), 0.5);
  eng::Model unscaled = normalMappedSquare(front, {128, 218, 218}, true);
  unscaled.materials[0].normalScale = 0.0f;
  EXPECT_LT(meanDifference(render(unscaled), plain), 0.5);
}

// glTF's occlusionTexture shades the ambient light alone, toward none as
// the strength falls.
TEST(OffscreenRender, OcclusionTextureDarkensTheAmbientLight) {
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](int red, float strength) {
    eng::Model model = testing_support::makeSphereModel({.targets = 0});
    if (red >= 0) {
      model.images.push_back({"occlusion", 1, 1, {uint8_t(red), 0, 0, 255}});
      model.materials.at(0).occlusionImage = 0;
      model.materials.at(0).occlusionStrength = strength;
    }
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const eng::Image open = render(-1, 1.0f), occluded = render(0, 1.0f);
  const glm::ivec4 lit = pixel(open, 90, 90), litOccluded = pixel(occluded, 90, 90);
  const glm::ivec4 away = pixel(open, 170, 170), awayOccluded = pixel(occluded, 170, 170);
  std::printf("occluded: %.2f levels darker on average; key side %d -> %d, far side %d -> %d (red)\n",
              meanDifference(open, occluded), lit.r, litOccluded.r, away.r, awayOccluded.r);
  EXPECT_GT(meanDifference(open, occluded), 1.0);  // the studio's ambient light is weak beside its key
  EXPECT_LT(awayOccluded.r, away.r);
  EXPECT_GT(litOccluded.r, lit.r / 2) << "the key light still reaches the occluded point";
  EXPECT_LT(meanDifference(open, render(255, 1.0f)), 0.05) << "occlusion 1: all the ambient light";
  EXPECT_LT(meanDifference(open, render(0, 0.0f)), 0.05) << "strength 0: no occlusion";
}

// glTF's emissiveTexture masks the emissive factor: black where the surface
// gives no light (a VRM's eye highlight painted on its texture), the factor
// where white.
TEST(OffscreenRender, EmissiveTextureMasksTheEmission) {
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](glm::vec3 factor, int grey) {
    eng::Model model = testing_support::makeSphereModel({.targets = 0});
    model.materials.at(0).emissiveFactor = factor;
    if (grey >= 0) {
      model.images.push_back({"glow", 1, 1, {uint8_t(grey), uint8_t(grey), uint8_t(grey), 255}});
      model.materials.at(0).emissiveImage = 0;
    }
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const glm::vec3 glow(0.0f, 0.0f, 0.6f);
  const eng::Image dark = render(glm::vec3(0.0f), -1), glowing = render(glow, -1);
  std::printf("emission %.2f levels from none; masked black %.2f, white %.2f from the factor alone\n",
              meanDifference(dark, glowing), meanDifference(dark, render(glow, 0)),
              meanDifference(glowing, render(glow, 255)));
  EXPECT_GT(meanDifference(dark, glowing), 5.0);
  EXPECT_LT(meanDifference(dark, render(glow, 0)), 0.05) << "black: no emission";
  EXPECT_LT(meanDifference(glowing, render(glow, 255)), 0.05) << "white: the factor";
}

TEST(OffscreenRender, UnlitMaterialShowsItsBaseColourEverywhere) {
  // KHR_materials_unlit: no light, shadow, exposure or tone curve. The lit
  // sphere is brighter toward the key and darker away from it; the unlit one
  // is its base colour (sRGB-encoded by the target) wherever it covers.
  const glm::vec4 colour{0.8f, 0.6f, 0.5f, 1.0f};
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](bool unlit) {
    auto gpu = uploadPlainSphere({.color = colour, .unlit = unlit});
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const eng::Image lit = render(false), unlit = render(true);
  const glm::ivec4 expected(231, 203, 188, 255);  // 0.8, 0.6, 0.5 linear in sRGB
  for (const glm::ivec2 p : {glm::ivec2(128, 128), glm::ivec2(90, 90), glm::ivec2(166, 166)}) {
    const glm::ivec4 got = pixel(unlit, p.x, p.y);
    EXPECT_LE(glm::compMax(glm::abs(got - expected)), 2) << "unlit at " << p.x << "," << p.y << ": " << got.r << " "
                                                         << got.g << " " << got.b;
  }
  const glm::ivec4 keySide = pixel(lit, 90, 90), farSide = pixel(lit, 166, 166);
  EXPECT_GT(keySide.r + keySide.g + keySide.b, farSide.r + farSide.g + farSide.b + 30) << "the lit sphere is shaded";
}

TEST(OffscreenRender, ToonMaterialShadesInTwoTonesWithItsShadeColour) {
  // MToon: toward the key the sphere is its base colour, away from it its
  // shade colour (a blue here, which no light of the rig gives a peach
  // surface), with a boundary as hard as the toony factor asks and nothing
  // of the skin shading's gradual fall-off either side of it.
  const glm::vec4 colour{0.8f, 0.6f, 0.5f, 1.0f};
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](std::optional<eng::ToonShading> toon) {
    auto gpu = uploadPlainSphere({.color = colour, .toon = toon});
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  eng::ToonShading toon;
  toon.shadeColor = {0.05f, 0.1f, 0.5f};
  toon.shadingToony = 0.95f;
  const eng::Image toonImage = render(toon), skin = render(std::nullopt);
  // The key comes from the upper left: the shade is the band along the lower right rim.
  const glm::ivec4 keySide = pixel(toonImage, 90, 90), farSide = pixel(toonImage, 186, 186);
  EXPECT_GT(keySide.r, keySide.b + 40) << "lit: the base colour";
  EXPECT_GT(farSide.b, farSide.r + 40) << "shade: the shade colour";
  // Across the lit part (the diagonal through the centre): the skin shading
  // falls off with the angle to the key, the toon shading stays one tone.
  auto spread = [](const eng::Image& image) {
    int lo = 255 * 3, hi = 0;
    for (int i = 60; i <= 170; ++i) {
      const glm::ivec4 p = pixel(image, i, i);
      lo = std::min(lo, p.r + p.g + p.b);
      hi = std::max(hi, p.r + p.g + p.b);
    }
    return hi - lo;
  };
  EXPECT_LE(spread(toonImage), 9) << "one flat tone";
  EXPECT_GE(spread(skin), 60) << "the skin shading falls off gradually";
}

TEST(OffscreenRender, ToonOutlineRingsTheSilhouetteAtTheWidthItAsksFor) {
  // A red outline with no lighting mix around a toon sphere: outside the
  // silhouette a red ring as wide as asked (world: 0.06 of the radius 1 at
  // about 98 px per unit; screen: 0.03 of the 256 px image height), inside
  // it nothing changes, the hull being behind the surface.
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](eng::ToonShading::OutlineWidth mode, float width) {
    eng::ToonShading toon;
    toon.shadeColor = {0.3f, 0.2f, 0.2f};
    toon.outlineMode = mode;
    toon.outlineWidth = width;
    toon.outlineColor = {1.0f, 0.0f, 0.0f};
    toon.outlineLightingMix = 0.0f;
    auto gpu = uploadPlainSphere({.toon = toon});
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  using Mode = eng::ToonShading::OutlineWidth;
  const eng::Image plain = render(Mode::None, 0.0f), world = render(Mode::World, 0.06f), screen = render(Mode::Screen, 0.03f);
  auto isRed = [](glm::ivec4 p) { return p.r > 150 && p.g < 60 && p.b < 60; };
  // The plain sphere's right edge on the middle row, then the ring beyond it.
  int edge = 128;
  while (edge < 255 && glm::compMax(glm::abs(pixel(plain, edge + 1, 128) - pixel(plain, 250, 128))) > 6) ++edge;
  ASSERT_GT(edge, 180) << "the sphere fills most of the image";
  auto ring = [&](const eng::Image& image) {
    int width = 0;
    while (edge + 1 + width < 256 && isRed(pixel(image, edge + 1 + width, 128))) ++width;
    return width;
  };
  EXPECT_EQ(ring(plain), 0);
  EXPECT_NEAR(ring(world), 6, 2) << "0.06 units";
  EXPECT_NEAR(ring(screen), 8, 2) << "0.03 x 256 px";
  for (const glm::ivec2 p : {glm::ivec2(128, 128), glm::ivec2(90, 90), glm::ivec2(166, 166)})
    EXPECT_LE(glm::compMax(glm::abs(pixel(world, p.x, p.y) - pixel(plain, p.x, p.y))), 2) << "inside at " << p.x << "," << p.y;
}

TEST(OffscreenRender, ToonMatcapLightsWhatFacesItsRowsOfTheImage) {
  // MToon's matcap is looked up by the view-space normal: a two-row image,
  // red above and blue below, adds red where the sphere faces up and blue
  // where it faces down (as matcaps are painted), scaled by matcapFactor,
  // and nothing without the texture.
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  auto render = [&](bool matcap, glm::vec3 factor) {
    eng::ToonShading toon;
    toon.shadeColor = {0.2f, 0.2f, 0.2f};
    toon.matcapFactor = factor;
    toon.rimLightingMix = 0.0f;  // added as it is: the test reads the matcap's own colours
    eng::Model model = testing_support::makeSphereModel({.targets = 0, .color = {0.2f, 0.2f, 0.2f, 1.0f}, .toon = toon});
    if (matcap) {
      model.images.push_back({"red over blue", 1, 2, {255, 0, 0, 255, 0, 0, 255, 255}});
      model.materials.at(0).matcapImage = int(model.images.size()) - 1;
    }
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const eng::Image plain = render(false, glm::vec3(1.0f)), lit = render(true, glm::vec3(1.0f)),
                   half = render(true, glm::vec3(0.5f));
  const glm::ivec4 top = pixel(lit, 128, 50) - pixel(plain, 128, 50), bottom = pixel(lit, 128, 206) - pixel(plain, 128, 206);
  std::printf("added at the top %d %d %d, at the bottom %d %d %d\n", top.r, top.g, top.b, bottom.r, bottom.g, bottom.b);
  // Measured +65 red against +19 blue at the top, the reverse at the bottom
  // (the two rows blend by the sampler, and the tone curve compresses).
  EXPECT_GT(top.r, top.b + 30) << "red where the sphere faces up";
  EXPECT_GT(bottom.b, bottom.r + 30) << "blue where it faces down";
  const glm::ivec4 topHalf = pixel(half, 128, 50) - pixel(plain, 128, 50);
  EXPECT_LT(topHalf.r, top.r - 10) << "matcapFactor scales it";
  EXPECT_GT(topHalf.r, 20);
}

TEST(OffscreenRender, ToonMasksScaleTheOutlineTheRimAndTheShadingShift) {
  // MToon's masks, one-pixel images over the whole sphere: the outline width
  // mask's green scales the ring (0: none, half: half as wide), the rim mask
  // multiplies the rim (black: as without a rim), and the shading shift
  // texture's red times its scale moves the light/shade boundary.
  const eng::vk::SceneView view = viewOf(eng::Aabb{{-1, -1, -1}, {1, 1, 1}});
  enum class Mask { None, Outline, Rim, Shift };
  auto render = [&](Mask mask, std::array<uint8_t, 4> texel, float rim, float shiftScale, bool outline = true) {
    eng::ToonShading toon;
    toon.shadeColor = {0.05f, 0.05f, 0.3f};
    toon.outlineMode = outline ? eng::ToonShading::OutlineWidth::World : eng::ToonShading::OutlineWidth::None;
    toon.outlineWidth = 0.08f;
    toon.outlineColor = {1.0f, 0.0f, 0.0f};
    toon.outlineLightingMix = 0.0f;
    toon.rimColor = glm::vec3(rim);
    toon.rimFresnelPower = 1.0f;
    toon.rimLightingMix = 0.0f;
    toon.shadingShiftTextureScale = shiftScale;
    eng::Model model = testing_support::makeSphereModel({.targets = 0, .color = {0.9f, 0.8f, 0.2f, 1.0f}, .toon = toon});
    if (mask != Mask::None) {
      model.images.push_back({"mask", 1, 1, {texel.begin(), texel.end()}});
      const int image = int(model.images.size()) - 1;
      eng::Material& mat = model.materials.at(0);
      (mask == Mask::Outline ? mat.outlineWidthImage : mask == Mask::Rim ? mat.rimMultiplyImage : mat.shadingShiftImage) = image;
    }
    auto gpu = vk_test::renderer().upload(model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), {}};
    return renderOrFail(view, {&instance, 1});
  };
  const std::array<uint8_t, 4> black{0, 0, 0, 255}, white{255, 255, 255, 255}, halfGreen{0, 128, 0, 255};
  // Outline: the ring beyond the sphere's right edge on the middle row.
  const eng::Image plain = render(Mask::None, white, 0.0f, 1.0f), bare = render(Mask::None, white, 0.0f, 1.0f, false);
  int edge = 128;
  while (edge < 255 && glm::compMax(glm::abs(pixel(bare, edge + 1, 128) - pixel(bare, 250, 128))) > 6) ++edge;
  ASSERT_GT(edge, 180) << "the sphere fills most of the image";
  auto ring = [&](const eng::Image& image) {
    int width = 0;
    while (edge + 1 + width < 256) {
      const glm::ivec4 p = pixel(image, edge + 1 + width, 128);
      if (!(p.r > 150 && p.g < 60 && p.b < 60)) break;
      ++width;
    }
    return width;
  };
  const int full = ring(plain), masked = ring(render(Mask::Outline, black, 0.0f, 1.0f)),
            half = ring(render(Mask::Outline, halfGreen, 0.0f, 1.0f)),
            unmasked = ring(render(Mask::Outline, white, 0.0f, 1.0f));
  std::printf("outline ring %d px, masked %d, half %d, white mask %d\n", full, masked, half, unmasked);
  EXPECT_GE(full, 6) << "0.08 units at about 98 px per unit";
  EXPECT_EQ(masked, 0) << "no line where the mask is black";
  EXPECT_NEAR(half, full / 2.0, 1.5) << "half as wide at half green";
  EXPECT_EQ(unmasked, full);
  // Rim: a grey rim whitens the yellow sphere toward its silhouette (blue
  // rises); a black mask takes it away, a white one keeps it.
  const glm::ivec2 nearEdge(edge - 4, 128);
  const glm::ivec4 noRim = pixel(plain, nearEdge.x, nearEdge.y),
                   rimmed = pixel(render(Mask::None, white, 0.6f, 1.0f), nearEdge.x, nearEdge.y),
                   rimBlack = pixel(render(Mask::Rim, black, 0.6f, 1.0f), nearEdge.x, nearEdge.y),
                   rimWhite = pixel(render(Mask::Rim, white, 0.6f, 1.0f), nearEdge.x, nearEdge.y);
  std::printf("near the edge: no rim %d, rim %d, black mask %d, white mask %d (blue)\n", noRim.b, rimmed.b, rimBlack.b,
              rimWhite.b);
  EXPECT_GT(rimmed.b, noRim.b + 25) << "the rim shows";
  EXPECT_LE(std::abs(rimBlack.b - noRim.b), 2) << "masked out";
  EXPECT_LE(std::abs(rimWhite.b - rimmed.b), 2) << "kept";
  // Shading shift: on the shaded lower right, a red texel times +1 moves the
  // boundary past it (the base colour's yellow), times -1 keeps the shade.
  const glm::ivec4 shaded = pixel(plain, 186, 186), lifted = pixel(render(Mask::Shift, white, 0.0f, 1.0f), 186, 186),
                   kept = pixel(render(Mask::Shift, white, 0.0f, -1.0f), 186, 186);
  std::printf("lower right: shaded %d %d %d, shifted +1 %d %d %d, -1 %d %d %d\n", shaded.r, shaded.g, shaded.b, lifted.r,
              lifted.g, lifted.b, kept.r, kept.g, kept.b);
  EXPECT_GT(shaded.b, shaded.r) << "the shade colour";
  EXPECT_GT(lifted.r, lifted.b + 60) << "lit: the base colour";
  EXPECT_GT(kept.b, kept.r) << "still the shade";
}

TEST(OffscreenRender, PrimitiveWithoutMaterialUsesTheDefault) {
  testing_support::SphereSpec spec;
  spec.withMaterial = false;
  const eng::Model model = testing_support::makeSphereModel(spec);
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  const eng::Image image = renderOrFail(viewOf(model.bounds()), {&instance, 1});
  const glm::ivec4 centre = pixel(image, 128, 128);
  EXPECT_GT(centre.g, 100) << "light neutral clay";
  EXPECT_LT(std::abs(centre.r - centre.g), 40);
}

TEST(OffscreenRender, AModelStagedOnceDrawsAsOneUploadedDirectly) {
  const eng::Model model = testing_support::makeSphereModel({});
  const VkPhysicalDeviceLimits& limits = vk_test::context().deviceInfo().properties.limits;
  auto staging = eng::vk::GpuModelStaging::build(model, limits);
  ASSERT_TRUE(staging) << staging.error().message;
  auto direct = vk_test::renderer().upload(model);
  auto first = vk_test::renderer().upload(model, *staging);
  auto second = vk_test::renderer().upload(model, *staging);
  ASSERT_TRUE(direct && first && second);
  std::vector<float> weights(direct->weightCount(), 0.0f);
  for (size_t t = 0; t < weights.size(); ++t) weights[t] = 0.3f + 0.2f * float(t % 3);
  const auto draw = [&](const eng::vk::GpuModel& gpu) {
    const eng::vk::ModelInstance instance{&gpu, glm::mat4(1.0f), weights};
    return renderOrFail(viewOf(model.bounds()), {&instance, 1});
  };
  const eng::Image expected = draw(*direct);
  EXPECT_EQ(draw(*first).rgba8, expected.rgba8);
  EXPECT_EQ(draw(*second).rgba8, expected.rgba8);
}

TEST(OffscreenRenderValidity, AStagingMustFitTheModelAndTheDevice) {
  const eng::Model sphere = testing_support::makeSphereModel({});
  VkPhysicalDeviceLimits limits = vk_test::context().deviceInfo().properties.limits;
  auto staging = eng::vk::GpuModelStaging::build(sphere, limits);
  ASSERT_TRUE(staging) << staging.error().message;
  // Another model (two meshes) is refused, naming both counts.
  eng::Model two = sphere;
  two.meshes.push_back(two.meshes.front());
  two.sourcePath = "two.glb";
  auto mismatched = vk_test::renderer().upload(two, *staging);
  ASSERT_FALSE(mismatched);
  EXPECT_NE(mismatched.error().message.find("two.glb: staged with 1 meshes, the model has 2"), std::string::npos)
      << mismatched.error().message;
  // A device that needs wider alignment than the staging was laid out with.
  limits.minStorageBufferOffsetAlignment = 1024;
  EXPECT_FALSE(staging->fits(limits));
  limits = vk_test::context().deviceInfo().properties.limits;
  limits.maxTexelBufferElements = 4;
  auto small = staging->fits(limits);
  ASSERT_FALSE(small);
  EXPECT_NE(small.error().message.find("the device allows 4"), std::string::npos) << small.error().message;
}

TEST(OffscreenRenderValidity, WrongWeightCountNamesTheSizes) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(3, 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  auto image = vk_test::renderer().render(viewOf(model.bounds()), {&instance, 1});
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().message.find("3 weights given, the model has 4"), std::string::npos)
      << image.error().message;
}

TEST(OffscreenRenderValidity, NonFiniteWeightAndNullModelAreErrors) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  std::vector<float> weights(4, 0.0f);
  weights[2] = std::numeric_limits<float>::quiet_NaN();
  const eng::vk::ModelInstance nan{&*gpu, glm::mat4(1.0f), weights};
  auto image = vk_test::renderer().render(viewOf(model.bounds()), {&nan, 1});
  ASSERT_FALSE(image);
  EXPECT_NE(image.error().message.find("weight 2 of 4 is not finite"), std::string::npos) << image.error().message;

  const eng::vk::ModelInstance none{nullptr, glm::mat4(1.0f), {}};
  auto noModel = vk_test::renderer().render(viewOf(model.bounds()), {&none, 1});
  ASSERT_FALSE(noModel);
  EXPECT_NE(noModel.error().message.find("instance 0: no model"), std::string::npos);
}

TEST(OffscreenRenderValidity, InconsistentModelIsRejectedByName) {
  eng::Model model = testing_support::makeSphereModel({});
  model.sourcePath = "broken.glb";
  model.meshes[0].primitives[0].indices.back() = 100000;
  auto gpu = vk_test::renderer().upload(model);
  ASSERT_FALSE(gpu);
  const std::string vertices = std::to_string(model.meshes[0].primitives[0].vertexCount());
  EXPECT_NE(gpu.error().message.find("broken.glb: mesh 0 'sphere' primitive 0: index 100000 at position "), std::string::npos)
      << gpu.error().message;
  EXPECT_NE(gpu.error().message.find("is out of range of " + vertices + " vertices"), std::string::npos)
      << gpu.error().message;

  eng::Model shortNormals = testing_support::makeSphereModel({});
  shortNormals.meshes[0].primitives[0].normals.pop_back();
  auto rejected = vk_test::renderer().upload(shortNormals);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("normals for"), std::string::npos) << rejected.error().message;

  eng::Model badTarget = testing_support::makeSphereModel({});
  badTarget.meshes[0].primitives[0].targets[1].positions.resize(5);
  auto targetError = vk_test::renderer().upload(badTarget);
  ASSERT_FALSE(targetError);
  EXPECT_NE(targetError.error().message.find("target 1"), std::string::npos) << targetError.error().message;
}

TEST(OffscreenTargetValidity, ZeroSizeIsAnError) {
  auto target = eng::vk::OffscreenTarget::create(vk_test::context(), 0, 64);
  ASSERT_FALSE(target);
  EXPECT_NE(target.error().message.find("0x64"), std::string::npos) << target.error().message;
}

}  // namespace
