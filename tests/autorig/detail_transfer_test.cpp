// The head's wrinkle and colour layers (texture cross-blending) carried onto
// a rigged face with its action units (autorig/detail_transfer.h): baked in
// the face's own UVs, as modulations of its own colour.
#include "autorig/detail_transfer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "autorig/posed_face.h"
#include "engine/core/uv_raster.h"
#include "tests/autorig/transfer_fixture.h"
#include "tests/common/test_support.h"

namespace {

using transfer_fixture::headSource;
using transfer_fixture::loadHead;
using transfer_fixture::stripped;

// The texel of `image` under `uv` (nearest, repeating): linear rgb, alpha.
glm::vec4 texelAt(const eng::Image& image, glm::vec2 uv) {
  uv -= glm::floor(uv);
  const int x = std::clamp(int(uv.x * float(image.width)), 0, image.width - 1);
  const int y = std::clamp(int(uv.y * float(image.height)), 0, image.height - 1);
  const uint8_t* t = &image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
  return {eng::srgbToLinear(t[0] / 255.0f), eng::srgbToLinear(t[1] / 255.0f), eng::srgbToLinear(t[2] / 255.0f),
          t[3] / 255.0f};
}

// The coverage of a carried (modulating) image's brightening texels (the
// modulation above 0.5: the skin lit up) and of its darkening ones, summed.
struct LightAndDark {
  double light = 0.0, dark = 0.0;
};
LightAndDark coverageOf(const eng::Image& carried) {
  LightAndDark out;
  for (size_t i = 0; i + 3 < carried.rgba8.size(); i += 4) {
    const uint8_t* t = &carried.rgba8[i];
    const float lum = 0.2126f * eng::srgbToLinear(t[0] / 255.0f) + 0.7152f * eng::srgbToLinear(t[1] / 255.0f) +
                      0.0722f * eng::srgbToLinear(t[2] / 255.0f);
    if (lum > 0.55f)
      out.light += t[3] / 255.0;
    else if (lum < 0.45f)
      out.dark += t[3] / 255.0;
  }
  return out;
}

const eng::Image* imageNamed(const eng::Model& model, const std::string& part) {
  for (const eng::Image& image : model.images)
    if (image.name.find(part) != std::string::npos) return &image;
  return nullptr;
}

const eng::Material* materialNamed(const eng::Model& model, const std::string& name) {
  for (const eng::Material& m : model.materials)
    if (m.name == name) return &m;
  return nullptr;
}

// The built-in head stripped of its targets (and of its layers, unless
// `keepLayers`), changed by `edit`, rigged from itself; `head` keeps the
// head as loaded. Nullopt, with a test failure, when a step fails.
std::optional<autorig::TransferResult> headRiggedOntoItself(eng::Model& head, bool keepLayers,
                                                            const std::function<void(eng::Model&)>& edit = {}) {
  std::optional<eng::Model> loaded = loadHead();
  if (!loaded) return std::nullopt;
  head = std::move(*loaded);
  const autorig::SourceFace source = headSource(head);
  eng::Model face = stripped(head);
  if (!keepLayers)
    for (eng::Material& m : face.materials) m.detailLayers.clear();
  if (edit) edit(face);
  auto rigged = autorig::transferTargets(source, face, source.posed, source.landmarks, source.parts);
  if (!rigged) {
    ADD_FAILURE() << rigged.error().message;
    return std::nullopt;
  }
  return std::move(*rigged);
}

// The head stripped of its targets and of its layers, rigged from itself:
// its skin gets its nine layers back, modulating, on the same targets, and
// each image's coverage lands where the head's own is painted (sampled at
// the skin's vertices: the correspondence of the head with itself is near
// the identity), a crease darkening the skin under it.
TEST(DetailTransfer, TheHeadStrippedOfItsLayersGetsThemBack) {
  eng::Model head;
  const std::optional<autorig::TransferResult> rigged = headRiggedOntoItself(head, false);
  ASSERT_TRUE(rigged);
  ASSERT_EQ(rigged->report.details.size(), 1u);
  EXPECT_NE(rigged->report.details[0].find("material 'Skin': 9 wrinkle and colour layers over 5 images"), std::string::npos)
      << rigged->report.details[0];
  const eng::Material* own = materialNamed(head, "Skin");
  const eng::Material* carried = materialNamed(rigged->model, "Skin");
  ASSERT_TRUE(own && carried);
  ASSERT_EQ(carried->detailLayers.size(), own->detailLayers.size());
  for (size_t l = 0; l < own->detailLayers.size(); ++l) {
    EXPECT_EQ(carried->detailLayers[l].target, own->detailLayers[l].target);
    EXPECT_EQ(carried->detailLayers[l].strength, own->detailLayers[l].strength);
    EXPECT_EQ(carried->detailLayers[l].blend, eng::DetailBlend::Modulate);
  }
  const eng::Primitive& skin = rigged->model.meshes[0].primitives[0];
  ASSERT_EQ(rigged->model.materials[size_t(skin.material)].name, "Skin");
  for (size_t l = 0; l < own->detailLayers.size(); ++l) {
    if (l > 0 && own->detailLayers[l].image == own->detailLayers[l - 1].image) continue;
    const eng::Image& ownImage = head.images[size_t(own->detailLayers[l].image)];
    const eng::Image& carriedImage = rigged->model.images[size_t(carried->detailLayers[l].image)];
    SCOPED_TRACE(ownImage.name);
    double ownCover = 0.0, apart = 0.0, creaseScale = 0.0;
    size_t creases = 0;
    for (const glm::vec2& uv : skin.texcoords) {
      const glm::vec4 a = texelAt(ownImage, uv), b = texelAt(carriedImage, uv);
      ownCover += a.a, apart += std::abs(a.a - b.a);
      if (ownImage.name == "skin_forehead_furrows" && a.a > 0.4f && b.a > 0.4f) creaseScale += 2.0 * b.g, ++creases;
    }
    ASSERT_GT(ownCover, 1.0);
    EXPECT_LT(apart / ownCover, 0.2) << "the carried coverage against the head's own, at the skin's vertices";
    if (creases > 0) {
      EXPECT_LT(creaseScale / double(creases), 0.85) << "a furrow darkens the skin under it";
    }
  }
  // A mesh as fine as the head's keeps the folds' narrow lit edges (lit
  // coverage 0.44 of the dark).
  const eng::Image* folds = imageNamed(rigged->model, "nasolabial_folds (carried)");
  ASSERT_TRUE(folds);
  const LightAndDark cover = coverageOf(*folds);
  EXPECT_GT(cover.light / cover.dark, 0.35) << "lit " << cover.light << " against dark " << cover.dark << " texels";
}

// facecap draws its eyes and teeth with its skin's material and has no
// texture (its UVs are quantized, 0-4095): the skin gets a copy of the
// material of its own, its UVs fitted into [0, 1], and the furrows land on
// its forehead, above its brows.
TEST(DetailTransfer, FacecapsSkinGetsTheLayersOnAMaterialOfItsOwn) {
  FACIAL_REQUIRE_SHARED();
  auto loaded = eng::loadModel(testing_support::sharedDir() / "assets/facecap.glb");
  ASSERT_TRUE(loaded) << loaded.error().message;
  const eng::Model bare = stripped(std::move(*loaded));
  autorig::FaceLandmarks landmarks;
  std::optional<autorig::TransferResult> rigged =
      transfer_fixture::rigWithFixtureLandmarks(bare, autorig::poseAtRest(bare), "facecap.landmarks.json", &landmarks);
  ASSERT_TRUE(rigged);
  const eng::Model& model = rigged->model;
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  const autorig::LandmarkFrame frame(landmarks);
  const float brows = glm::dot(landmarks.points[19] + landmarks.points[24] - 2.0f * frame.origin(), frame.up()) * 0.5f;
  size_t layered = 0, onTheForehead = 0, furrowed = 0;
  for (const autorig::PosedPrimitive& pp : posed.primitives) {
    const eng::Primitive& prim = model.meshes[pp.mesh].primitives[pp.primitive];
    const eng::Material& m = model.materials[size_t(prim.material)];
    if (m.detailLayers.empty()) continue;
    ++layered;
    EXPECT_EQ(m.name, "lambert5 (skin)");
    EXPECT_FALSE(model.meshes[pp.mesh].targetNames.empty());
    for (const glm::vec2& uv : prim.texcoords) EXPECT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f);
    // Where on the face each furrowed texel lies (the creases are thinner
    // than facecap's triangles: texels, not vertices).
    const eng::Image& furrows = model.images[size_t(m.detailLayers[0].image)];  // AU1's
    eng::rasterizeUv(furrows.width, furrows.height, prim.texcoords, prim.indices,
                     [&](int x, int y, uint32_t tri, const glm::vec3& b) {
                       if (furrows.rgba8[(size_t(y) * size_t(furrows.width) + size_t(x)) * 4 + 3] < 77) return;
                       const uint32_t* t = &prim.indices[size_t(tri) * 3];
                       const glm::vec3 p = b.x * pp.positions[t[0]] + b.y * pp.positions[t[1]] + b.z * pp.positions[t[2]];
                       ++furrowed;
                       onTheForehead += glm::dot(p - frame.origin(), frame.up()) > brows;
                     });
  }
  EXPECT_EQ(layered, 1u) << "the skin alone";
  ASSERT_GT(furrowed, 10u);
  EXPECT_GT(double(onTheForehead) / double(furrowed), 0.95) << onTheForehead << " of " << furrowed;
  // facecap's edges are about twice as long as the head's: it cannot fold
  // where the head's nasolabial folds do, and their narrow lit edge alone
  // drew a pale outline about its mouth. It is carried fainter (lit
  // coverage 0.08 of the dark, the crease spread beside it; 0.37 with both
  // as painted, 0.44 on the head rigged onto itself).
  const eng::Image* folds = imageNamed(model, "nasolabial_folds (carried)");
  ASSERT_TRUE(folds);
  const LightAndDark cover = coverageOf(*folds);
  EXPECT_LT(cover.light / cover.dark, 0.25) << "lit " << cover.light << " against dark " << cover.dark << " texels";
}

// A layer for a coarse mesh (autorig::layerForACoarseMesh): a narrow crease
// spreads into a softer shade of its own colour, no darker than it was; a
// broad darkening keeps its coverage; a narrow highlight fades; what was
// left unpainted stays so.
TEST(DetailTransfer, ACoarseMeshGetsSofterCreasesAndNoNarrowHighlights) {
  const int size = 1024;
  eng::Image painted;
  painted.width = painted.height = size;
  painted.rgba8.assign(size_t(size) * size_t(size) * 4, 0);
  auto paint = [&](int x0, int x1, const glm::vec3& colour, float coverage) {
    for (int y = 100; y < 900; ++y)
      for (int x = x0; x < x1; ++x) {
        uint8_t* t = &painted.rgba8[(size_t(y) * size_t(size) + size_t(x)) * 4];
        for (int k = 0; k < 3; ++k) t[k] = uint8_t(std::lround(255.0f * eng::linearToSrgb(colour[k])));
        t[3] = uint8_t(std::lround(255.0f * coverage));
      }
  };
  const glm::vec3 tone(0.5f, 0.4f, 0.35f), crease(0.2f, 0.1f, 0.08f);
  paint(100, 102, crease, 0.8f);                       // a crease two texels wide
  paint(300, 302, glm::vec3(0.9f, 0.8f, 0.7f), 0.8f);  // a highlight as narrow
  paint(500, 700, glm::vec3(0.3f, 0.2f, 0.2f), 0.5f);  // a broad darkening
  const eng::Image coarse = autorig::layerForACoarseMesh(painted, tone);
  ASSERT_EQ(coarse.rgba8.size(), painted.rgba8.size());
  auto at = [&](const eng::Image& image, int x) { return texelAt(image, {(float(x) + 0.5f) / size, 0.5f}); };

  const glm::vec4 onTheCrease = at(coarse, 100), beside = at(coarse, 105);
  EXPECT_LE(onTheCrease.a, 0.8f + 0.5f / 255.0f) << "no darker than the crease";
  EXPECT_GT(onTheCrease.a, 0.4f) << "the crease still reads";
  EXPECT_GT(beside.a, 0.1f) << "spread 4 texels beside it";
  EXPECT_EQ(at(painted, 105).a, 0.0f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(beside[k], crease[k], 0.01f) << "its own colour, channel " << k;
  EXPECT_EQ(at(coarse, 120).a, 0.0f) << "far from it, unpainted";

  EXPECT_NEAR(at(coarse, 600).a, 0.5f, 1.0f / 255.0f) << "a broad darkening as it was";
  EXPECT_LT(at(coarse, 300).a, 0.3f) << "a narrow highlight fades";
}

// A face whose skin has layers of its own keeps them, untouched.
TEST(DetailTransferValidity, AFaceWithLayersOfItsOwnKeepsThem) {
  eng::Model head;
  const std::optional<autorig::TransferResult> rigged = headRiggedOntoItself(head, true);
  ASSERT_TRUE(rigged);
  EXPECT_TRUE(rigged->report.details.empty());
  EXPECT_TRUE(std::any_of(rigged->report.warnings.begin(), rigged->report.warnings.end(), [](const std::string& w) {
    return w == "material 'Skin' has detail layers of its own: the head's wrinkle and colour layers are not carried onto it";
  }));
  EXPECT_EQ(rigged->model.images.size(), head.images.size());
  const eng::Material* skin = materialNamed(rigged->model, "Skin");
  ASSERT_TRUE(skin);
  ASSERT_EQ(skin->detailLayers.size(), 9u);
  for (const eng::DetailLayer& layer : skin->detailLayers) EXPECT_EQ(layer.blend, eng::DetailBlend::Mix);
}

// A skin without UVs gets none, with a warning that says why.
TEST(DetailTransferValidity, ASkinWithoutUvsGetsNoLayers) {
  eng::Model head;
  const std::optional<autorig::TransferResult> rigged = headRiggedOntoItself(head, false, [](eng::Model& face) {
    for (eng::Mesh& mesh : face.meshes)
      for (eng::Primitive& p : mesh.primitives) p.texcoords.clear();
  });
  ASSERT_TRUE(rigged);
  EXPECT_TRUE(rigged->report.details.empty());
  EXPECT_TRUE(std::any_of(rigged->report.warnings.begin(), rigged->report.warnings.end(), [](const std::string& w) {
    return w.find("material 'Skin' has no UVs on the face's skin") != std::string::npos;
  }));
  for (const eng::Material& m : rigged->model.materials) EXPECT_TRUE(m.detailLayers.empty()) << m.name;
}

// A skin whose triangles each span the whole UV square (a hostile or broken
// file) would cost a pass over every texel per triangle: refused, with a
// warning, in bounded time.
TEST(DetailTransferValidity, UvsThatOverlapOverAndOverGetNoLayers) {
  eng::Model head;
  const std::optional<autorig::TransferResult> rigged = headRiggedOntoItself(head, false, [](eng::Model& face) {
    eng::Primitive& skin = face.meshes[0].primitives[0];
    for (size_t v = 0; v < skin.texcoords.size(); ++v)
      skin.texcoords[v] = v % 3 == 0 ? glm::vec2(0.0f) : v % 3 == 1 ? glm::vec2(1.0f, 0.0f) : glm::vec2(0.0f, 1.0f);
  });
  ASSERT_TRUE(rigged);
  EXPECT_TRUE(rigged->report.details.empty());
  EXPECT_TRUE(std::any_of(rigged->report.warnings.begin(), rigged->report.warnings.end(), [](const std::string& w) {
    return w.find("material 'Skin''s UVs overlap") != std::string::npos;
  }));
}

}  // namespace
