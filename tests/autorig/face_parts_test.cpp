// A face's parts told apart by name and, without names, by shape: eyeballs
// as spheres behind the lids (the subject's right one behind landmarks
// 36-41), teeth inside the mouth split at the mouth line, far parts left out.
#include "autorig/face_parts.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "tests/common/test_meshes.h"

namespace {

// Landmarks laid on testing_support::plasterHead(): eyes over its eyeballs
// (x = -0.35 is the subject's right), the mouth line through its teeth.
autorig::FaceLandmarks plasterLandmarks() {
  autorig::FaceLandmarks l;
  for (size_t i = 0; i <= 16; ++i) {  // jaw, ear to ear under the chin
    const float a = glm::pi<float>() * float(i) / 16.0f;
    l.points[i] = {-0.8f * std::cos(a), -0.1f - 0.7f * std::sin(a), 0.6f};
  }
  for (size_t i = 17; i <= 26; ++i) l.points[i] = {-0.55f + 0.11f * float(i - 17) + (i > 21 ? 0.1f : 0.0f), 0.4f, 0.9f};
  for (size_t i = 27; i <= 35; ++i) l.points[i] = {0.0f, 0.2f - 0.06f * float(i - 27), 0.98f};
  for (int side = 0; side < 2; ++side) {
    const float cx = side == 0 ? -0.35f : 0.35f;
    const size_t first = side == 0 ? 36 : 42;
    const float xs[6] = {-0.15f, -0.05f, 0.05f, 0.15f, 0.05f, -0.05f};
    const float ys[6] = {0.0f, 0.05f, 0.05f, 0.0f, -0.05f, -0.05f};
    for (size_t k = 0; k < 6; ++k) l.points[first + k] = {cx + xs[k], 0.2f + ys[k], 0.93f};
  }
  for (size_t i = 48; i <= 67; ++i) {
    const float a = 2.0f * glm::pi<float>() * float(i - 48) / (i < 60 ? 12.0f : 8.0f);
    const float w = i < 60 ? 0.25f : 0.18f, h = i < 60 ? 0.08f : 0.02f;
    l.points[i] = {-w * std::cos(a), -0.4f + h * std::sin(a), 0.92f};
  }
  return l;
}

size_t count(const std::vector<autorig::FacePart>& parts, autorig::FacePart part) {
  return size_t(std::count(parts.begin(), parts.end(), part));
}

void expectPlasterParts(const eng::Model& model, const autorig::FaceParts& parts) {
  using autorig::FacePart;
  ASSERT_EQ(parts.vertexParts.size(), 11u);
  const FacePart others[] = {FacePart::Glasses, FacePart::Hair, FacePart::Brows, FacePart::Brows, FacePart::Lashes, FacePart::Lashes};
  for (size_t i = 5; i < 11; ++i)
    EXPECT_EQ(count(parts.vertexParts[i], others[i - 5]), parts.vertexParts[i].size()) << "part " << i;
  const auto& head = parts.vertexParts[0];
  EXPECT_EQ(count(head, FacePart::Skin), head.size());
  EXPECT_EQ(count(parts.vertexParts[1], FacePart::EyeballLeft), parts.vertexParts[1].size());  // at +x
  EXPECT_EQ(count(parts.vertexParts[2], FacePart::EyeballRight), parts.vertexParts[2].size());
  const auto& teeth = parts.vertexParts[3];
  EXPECT_GT(count(teeth, FacePart::UpperTeeth), teeth.size() / 3);
  EXPECT_GT(count(teeth, FacePart::LowerTeeth), teeth.size() / 3);
  EXPECT_EQ(count(teeth, FacePart::UpperTeeth) + count(teeth, FacePart::LowerTeeth), teeth.size());
  EXPECT_EQ(count(parts.vertexParts[4], FacePart::Other), parts.vertexParts[4].size());
  ASSERT_TRUE(parts.eyeballsFound);
  EXPECT_LT(glm::distance(parts.eyeCentres[0], glm::vec3(-0.35f, 0.2f, 0.85f)), 0.01f);
  EXPECT_LT(glm::distance(parts.eyeCentres[1], glm::vec3(0.35f, 0.2f, 0.85f)), 0.01f);
  EXPECT_NEAR(parts.eyeRadii[0], 0.12f, 0.01f);
  (void)model;
}

// The plaster head with `piece` added as a mesh of its own and every name
// gone, its parts (the piece's last).
autorig::FaceParts partsOfThePlasterHeadUnnamedWith(const eng::Primitive& piece) {
  eng::Model model = testing_support::plasterHead();
  eng::Mesh mesh;
  mesh.primitives.push_back(piece);
  eng::Model part;
  part.meshes.push_back(mesh);
  testing_support::addPartAsRoot(model, std::move(part), "", glm::vec3(0.0f), glm::vec3(1.0f));
  for (eng::Node& n : model.nodes) n.name.clear();
  for (eng::Mesh& m : model.meshes) m.name.clear();
  for (eng::Material& m : model.materials) m.name.clear();
  return autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
}

// Triangles over a side x side grid of vertices from `first`, row by row.
void addGridTriangles(eng::Primitive& p, uint32_t first, uint32_t side) {
  for (uint32_t j = 0; j + 1 < side; ++j)
    for (uint32_t i = 0; i + 1 < side; ++i) {
      const uint32_t a = first + j * side + i, b = a + 1, c = a + side, d = c + 1;
      p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
    }
}

// With a prop far away (Other), a bar across the eyes (glasses), a cap over
// the head (hair), brow cards and lash strips.
eng::Model plasterHeadWithProp() {
  eng::Model model = testing_support::plasterHead();
  testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), "prop",
                                 {6.0f, 0.0f, 0.0f}, glm::vec3(0.5f));
  testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), "glasses",
                                 {0.0f, 0.2f, 1.05f}, glm::vec3(0.6f, 0.03f, 0.03f));
  const auto add = [&](const char* name, glm::vec3 at, glm::vec3 scale) {
    testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), name,
                                   at, scale);
  };
  add("hair", {0.0f, 0.7f, -0.1f}, {1.05f, 0.5f, 1.05f});
  add("browRight", {-0.33f, 0.42f, 0.95f}, {0.15f, 0.02f, 0.02f});
  add("browLeft", {0.33f, 0.42f, 0.95f}, {0.15f, 0.02f, 0.02f});
  add("lashRight", {-0.35f, 0.26f, 0.95f}, {0.12f, 0.01f, 0.01f});
  add("lashLeft", {0.35f, 0.26f, 0.95f}, {0.12f, 0.01f, 0.01f});
  return model;
}

TEST(FaceParts, ByName) {
  const eng::Model model = plasterHeadWithProp();
  const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
  expectPlasterParts(model, parts);
}

// The same head with every name gone: the shapes alone tell the parts apart.
TEST(FaceParts, ByShape) {
  eng::Model model = plasterHeadWithProp();
  for (eng::Node& n : model.nodes) n.name.clear();
  for (eng::Mesh& m : model.meshes) m.name.clear();
  for (eng::Material& m : model.materials) m.name.clear();
  const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
  expectPlasterParts(model, parts);
  EXPECT_FALSE(parts.notes.empty());
}

// Eyeballs that are pieces of the mesh called "head": found by shape.
TEST(FaceParts, EyeballsInsideTheHeadMesh) {
  eng::Model model = testing_support::plasterHead();
  eng::Primitive& head = model.meshes[0].primitives[0];
  head.targets.clear();
  model.meshes[0].targetNames.clear();
  model.meshes[0].defaultWeights.clear();
  for (size_t eye = 1; eye <= 2; ++eye) {
    const glm::mat4 place = model.worldTransform(int(eye));
    const eng::Primitive& ball = model.meshes[eye].primitives[0];
    const uint32_t first = uint32_t(head.positions.size());
    for (size_t v = 0; v < ball.positions.size(); ++v) {
      head.positions.push_back(glm::vec3(place * glm::vec4(ball.positions[v], 1.0f)));
      head.normals.push_back(ball.normals[v]);
      if (!head.texcoords.empty()) head.texcoords.push_back(ball.texcoords.empty() ? glm::vec2(0.0f) : ball.texcoords[v]);
    }
    for (uint32_t i : ball.indices) head.indices.push_back(first + i);
  }
  model.nodes[1].mesh = model.nodes[2].mesh = -1;  // the eyes' own meshes no longer drawn
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  const autorig::FaceParts parts = autorig::findFaceParts(model, posed, plasterLandmarks());
  ASSERT_FALSE(parts.vertexParts.empty());
  const auto& v = parts.vertexParts[0];
  const size_t ball = model.meshes[1].primitives[0].vertexCount();
  EXPECT_EQ(count(v, autorig::FacePart::EyeballLeft), ball);
  EXPECT_EQ(count(v, autorig::FacePart::EyeballRight), ball);
  EXPECT_EQ(count(v, autorig::FacePart::Skin), v.size() - 2 * ball);
  EXPECT_TRUE(parts.eyeballsFound);
}

// No eyeball meshes: the balls are estimated behind the lid lines.
TEST(FaceParts, EyeballsEstimatedWithoutMeshes) {
  const eng::Model model = testing_support::makeSphereModel(testing_support::whiteSphereSpec(0));
  const autorig::FaceLandmarks l = plasterLandmarks();
  const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), l);
  EXPECT_FALSE(parts.eyeballsFound);
  EXPECT_FALSE(parts.eyesInTheSkin[0] || parts.eyesInTheSkin[1]);
  EXPECT_GT(parts.eyeRadii[0], 0.0f);
  EXPECT_LT(parts.eyeCentres[0].z, l.points[36].z);
  EXPECT_LT(parts.eyeCentres[0].x, 0.0f);
  EXPECT_GT(parts.eyeCentres[1].x, 0.0f);
}

// A scan's eyes are its skin: one sheet whose eye openings are filled by the
// fronts of two balls (radius 0.2, behind the plaster landmarks' lid lines).
// The skin on each ball inside the lids is that eyeball, the rest stays
// skin, and the balls are fitted from it.
TEST(FaceParts, EyesThatAreTheSkin) {
  constexpr float kRadius = 0.2f, kCentreZ = 0.77f, kFace = 0.98f;
  eng::Primitive sheet = testing_support::flatSheet(161);
  auto inOpening = [](const glm::vec3& p, float scale) {
    const float dx = std::abs(p.x) - 0.35f, dy = p.y - 0.2f;
    return (dx / 0.16f) * (dx / 0.16f) + (dy / 0.058f) * (dy / 0.058f) < scale * scale;
  };
  for (glm::vec3& p : sheet.positions) {
    p = glm::vec3(p.x * 1.6f, p.y * 1.6f, kFace);
    if (!inOpening(p, 1.0f)) continue;
    const float dx = std::abs(p.x) - 0.35f, dy = p.y - 0.2f;
    p.z = kCentreZ + std::sqrt(kRadius * kRadius - dx * dx - dy * dy);
  }
  eng::Mesh mesh;
  mesh.primitives.push_back(sheet);
  const eng::Model model = testing_support::singleMeshModel(mesh);
  const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
  ASSERT_EQ(parts.vertexParts.size(), 1u);
  size_t wrong = 0, inner = 0;
  for (size_t v = 0; v < sheet.positions.size(); ++v) {
    const glm::vec3& p = sheet.positions[v];
    const autorig::FacePart part = parts.vertexParts[0][v];
    const autorig::FacePart ball = p.x < 0.0f ? autorig::FacePart::EyeballRight : autorig::FacePart::EyeballLeft;
    if (!inOpening(p, 1.0f)) wrong += part != autorig::FacePart::Skin;
    else if (inOpening(p, 0.9f)) wrong += part != ball, ++inner;
  }
  EXPECT_GT(inner, 100u);
  EXPECT_EQ(wrong, 0u) << "the lids are skin, the balls inside them eyeballs";
  EXPECT_TRUE(parts.eyeballsFound);
  for (size_t e = 0; e < 2; ++e) {
    EXPECT_TRUE(parts.eyesInTheSkin[e]) << e;
    EXPECT_LT(glm::distance(parts.eyeCentres[e], glm::vec3(e == 0 ? -0.35f : 0.35f, 0.2f, kCentreZ)), 0.01f) << e;
    EXPECT_NEAR(parts.eyeRadii[e], kRadius, 0.01f) << e;
  }
  EXPECT_TRUE(std::any_of(parts.notes.begin(), parts.notes.end(),
                          [](const std::string& n) { return n.find("a scan's eye") != std::string::npos; }));
}

// A face without eyeballs whose skin runs flat over the eyes (painted eyes):
// nothing of it is taken for an eyeball, the balls are estimated.
TEST(FaceParts, PaintedEyesAreSkin) {
  eng::Primitive sheet = testing_support::flatSheet(161);
  for (glm::vec3& p : sheet.positions) p = glm::vec3(p.x * 1.6f, p.y * 1.6f, 0.95f);
  eng::Mesh mesh;
  mesh.primitives.push_back(sheet);
  const eng::Model model = testing_support::singleMeshModel(mesh);
  const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
  ASSERT_EQ(parts.vertexParts.size(), 1u);
  EXPECT_EQ(count(parts.vertexParts[0], autorig::FacePart::Skin), sheet.positions.size());
  EXPECT_FALSE(parts.eyeballsFound);
  EXPECT_GT(parts.eyeRadii[0], 0.0f);
}

// A layer on the skin is told by its name, whatever its shape: a soul patch
// below the lips lies in the mouth's box, where an unnamed piece is teeth.
TEST(FaceParts, ALayerOnTheSkinIsToldByItsName) {
  using autorig::FacePart;
  for (const char* name : {"Wolf3D_Beard", "Moustache", "stubble_geo", "Wolf3D_Facewear", "face_makeup"}) {
    eng::Model model = testing_support::plasterHead();
    testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), name,
                                   {0.0f, -0.45f, 0.95f}, glm::vec3(0.05f, 0.02f, 0.01f));
    model.meshes.back().name = name;
    const autorig::FaceParts parts = autorig::findFaceParts(model, autorig::poseAtRest(model), plasterLandmarks());
    ASSERT_EQ(parts.vertexParts.size(), model.meshes.size());
    EXPECT_EQ(count(parts.vertexParts.back(), FacePart::SkinLayer), parts.vertexParts.back().size()) << name;
  }
  EXPECT_STREQ(autorig::facePartName(FacePart::SkinLayer), "layer on the skin");
}

// Without names, a piece lying just off the skin on its outside is a layer
// on it: a soul patch on the chin, in the mouth's box, is no row of teeth (a
// beard merged into an avatar's one primitive, as a texture atlas exports it).
TEST(FaceParts, AnUnnamedLayerOnTheSkinIsToldByWhereItLies) {
  eng::Primitive patch;
  constexpr int kSide = 6;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const float x = -0.1f + 0.2f * float(i) / float(kSide - 1), y = -0.58f + 0.1f * float(j) / float(kSide - 1);
      const float r = 1.015f;  // the head's unit sphere, 1.5% of its radius out
      const glm::vec3 p(x, y, std::sqrt(r * r - x * x - y * y));
      patch.positions.push_back(p);
      patch.normals.push_back(glm::normalize(p));
    }
  addGridTriangles(patch, 0, uint32_t(kSide));
  const autorig::FaceParts parts = partsOfThePlasterHeadUnnamedWith(patch);
  ASSERT_EQ(parts.vertexParts.size(), 5u);
  EXPECT_EQ(count(parts.vertexParts[4], autorig::FacePart::SkinLayer), patch.positions.size());
  EXPECT_EQ(count(parts.vertexParts[0], autorig::FacePart::Skin), parts.vertexParts[0].size());
  const auto& teeth = parts.vertexParts[3];
  EXPECT_EQ(count(teeth, autorig::FacePart::UpperTeeth) + count(teeth, autorig::FacePart::LowerTeeth), teeth.size());
}

// Glasses merged into one primitive with nothing else to tell them (a
// texture atlas's transparent primitive): their lenses are shallow caps of a
// sphere wider than themselves, no eyeballs, and the pair is glasses. Taken
// for eyeballs, they put the eyes' centres in front of the face.
TEST(FaceParts, LensesAreNoEyeballs) {
  eng::Primitive glasses;
  for (const float cx : {-0.35f, 0.35f}) {
    const uint32_t first = uint32_t(glasses.positions.size());
    constexpr int kSide = 7;
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        const float x = -0.13f + 0.26f * float(i) / float(kSide - 1), y = -0.1f + 0.2f * float(j) / float(kSide - 1);
        const float r = 0.6f;  // a cap of a sphere 0.6 wide about a point behind the lens
        glasses.positions.push_back({cx + x, 0.2f + y, 1.1f - r + std::sqrt(r * r - x * x - y * y)});
        glasses.normals.push_back({0.0f, 0.0f, 1.0f});
      }
    addGridTriangles(glasses, first, uint32_t(kSide));
  }
  const autorig::FaceParts parts = partsOfThePlasterHeadUnnamedWith(glasses);
  ASSERT_EQ(parts.vertexParts.size(), 5u);
  EXPECT_EQ(count(parts.vertexParts[4], autorig::FacePart::Glasses), glasses.positions.size());
  EXPECT_LT(glm::distance(parts.eyeCentres[0], glm::vec3(-0.35f, 0.2f, 0.85f)), 0.01f);
  EXPECT_LT(glm::distance(parts.eyeCentres[1], glm::vec3(0.35f, 0.2f, 0.85f)), 0.01f);
}

TEST(FaceParts, NamesOfParts) {
  EXPECT_STREQ(autorig::facePartName(autorig::FacePart::EyeballLeft), "left eyeball");
  EXPECT_STREQ(autorig::facePartName(autorig::FacePart::Other), "other");
}

}  // namespace
