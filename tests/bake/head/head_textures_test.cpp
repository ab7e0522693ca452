// The built-in head's painted textures: a warm skin tone, eyes that read as
// eyes (white sclera, coloured iris, dark pupil), dark mouth interior, and
// one detail layer image per painted layer, transparent where it has nothing.
#include <gtest/gtest.h>

#include <set>

#include "bake/head/skin_painter.h"
#include "tests/bake/head/built_in_head.h"

namespace {

const eng::Image& imageOfMaterial(const std::string& material) {
  const eng::Model& model = head_testing::builtInHead().model;
  for (const eng::Material& m : model.materials)
    if (m.name == material) return model.images.at(static_cast<size_t>(m.baseColorImage));
  throw std::runtime_error("no material " + material);
}

glm::vec4 texel(const eng::Image& img, float u, float v) {
  const int x = std::min(img.width - 1, int(u * img.width)), y = std::min(img.height - 1, int(v * img.height));
  const uint8_t* p = &img.rgba8[(size_t(y) * img.width + x) * 4];
  return glm::vec4(p[0], p[1], p[2], p[3]);
}

TEST(HeadTextures, SkinIsWarm) {
  const eng::Image& skin = imageOfMaterial("Skin");
  ASSERT_EQ(skin.rgba8.size(), size_t(skin.width) * skin.height * 4);
  // The cheek, a quarter of the way around from the front, below the eyes.
  glm::dvec3 sum(0.0);
  const int n = 50;
  for (int i = 0; i < n; ++i) sum += glm::dvec3(texel(skin, 0.58f + 0.001f * i, 0.55f));
  sum /= double(n);
  EXPECT_GT(sum.r, sum.g);
  EXPECT_GT(sum.g, sum.b);
  EXPECT_GT(sum.r, 170.0);
}

TEST(HeadTextures, EyesHaveWhiteScleraColouredIrisDarkPupil) {
  // Layout: u around the gaze axis, v = angle from it (0 at the pupil).
  const eng::Image& eye = imageOfMaterial("Eye");
  const glm::vec4 pupil = texel(eye, 0.3f, 0.02f);
  const glm::vec4 iris = texel(eye, 0.7f, 0.10f);
  const glm::vec4 sclera = texel(eye, 0.7f, 0.40f);
  EXPECT_LT(pupil.r + pupil.g + pupil.b, 60.0f);
  EXPECT_GT(sclera.r, 200.0f);
  EXPECT_GT(sclera.g, 190.0f);
  EXPECT_GT(sclera.b, 180.0f);
  EXPECT_GT(iris.r, iris.b + 30.0f) << "hazel-brown iris";
  // Dark enough to keep its weight in grey at 256 px.
  EXPECT_LT(iris.r + iris.g + iris.b, sclera.r + sclera.g + sclera.b - 300.0f);
}

TEST(HeadTextures, MouthInteriorDarkensInward) {
  const eng::Image& mouth = imageOfMaterial("MouthInterior");
  const glm::vec4 lip = texel(mouth, 0.5f, 0.02f), back = texel(mouth, 0.5f, 0.9f);
  EXPECT_GT(lip.r, back.r + 80.0f);
  EXPECT_LT(back.r + back.g + back.b, 120.0f);
  EXPECT_GT(back.r, back.b);
}

TEST(HeadTextures, DetailLayersAreDrivenByActionUnitsAndMostlyTransparent) {
  const eng::Model& model = head_testing::builtInHead().model;
  const eng::Material* skin = nullptr;
  for (const eng::Material& m : model.materials)
    if (m.name == "Skin") skin = &m;
  ASSERT_NE(skin, nullptr);
  ASSERT_FALSE(skin->detailLayers.empty());
  const eng::Mesh& head = head_testing::headMesh(model);
  std::set<int> images;
  for (const eng::DetailLayer& layer : skin->detailLayers) {
    EXPECT_GE(head_testing::targetIndex(head, layer.target), 0) << layer.target;
    EXPECT_GT(layer.strength, 0.0f);
    images.insert(layer.image);
  }
  EXPECT_EQ(images.size(), bake::skinDetailLayerNames().size());
  for (int i : images) {
    const eng::Image& img = model.images.at(static_cast<size_t>(i));
    size_t opaque = 0, transparent = 0;
    for (size_t p = 3; p < img.rgba8.size(); p += 4) (img.rgba8[p] > 20 ? opaque : transparent)++;
    EXPECT_GT(opaque, 200u) << img.name << " paints nothing";
    // Colour washes (flush, pallor) cover the face; wrinkles only lines of it.
    EXPECT_GT(transparent, (opaque + transparent) / 4) << img.name << " covers the whole head";
    const bool wrinkles = img.name.find("flush") == std::string::npos && img.name.find("pallor") == std::string::npos;
    if (wrinkles) {
      EXPECT_GT(transparent, 4 * opaque) << img.name << " covers too much";
    }
  }
}

}  // namespace
