// How untextured faces are shown (importers/face_dressing.h,
// procedural_eyes.h, painted_brows.h, vertex_occlusion.h), on models built
// here: a plaster head of spheres (tests/common/test_meshes.h).
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "importers/face_dressing.h"
#include "importers/painted_brows.h"
#include "importers/procedural_eyes.h"
#include "importers/vertex_occlusion.h"
#include "tests/common/test_meshes.h"

namespace {

using testing_support::addPartAsRoot;
using testing_support::makeSphereModel;
using testing_support::plasterHead;
using testing_support::whiteSphereSpec;

TEST(ProceduralEyes, UntexturedEyeballsAreFoundByNameAndShape) {
  const eng::Model model = plasterHead();
  const std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(model);
  ASSERT_EQ(eyes.size(), 2u);
  for (const importers::EyePrimitive& eye : eyes) {
    EXPECT_NEAR(eye.radius, 1.0f, 0.02f) << "sphere fit in mesh space";
    EXPECT_NEAR(eye.gazeAxis.z, 1.0f, 1e-4f) << "the face looks along +Z";
  }
}

// A face its file holds turned 30° aside and rolled 20°: its eyes look
// square to the line between them, where the face looks, not along +Z.
TEST(ProceduralEyes, AFaceTurnedInItsFileLooksWhereItFaces) {
  eng::Model model = plasterHead();
  const glm::quat turn = glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0)) *
                         glm::angleAxis(glm::radians(20.0f), glm::vec3(0, 0, 1));
  eng::turnAtRoots(model, turn);
  const std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(model);
  ASSERT_EQ(eyes.size(), 2u);
  const glm::vec3 facing = turn * glm::vec3(0.0f, 0.0f, 1.0f);
  for (const importers::EyePrimitive& eye : eyes) {
    const glm::vec3 gaze = glm::normalize(glm::mat3(model.worldTransform(eye.node)) * eye.gazeAxis);
    EXPECT_GT(glm::dot(gaze, facing), std::cos(glm::radians(1.0f))) << gaze.x << " " << gaze.y << " " << gaze.z;
  }
}

// Names lost on export ("mesh_1", "Object_2"): the pair of balls of one
// size, level and a few radii apart inside the head are its eyes.
eng::Model withoutNames(eng::Model model) {
  for (size_t i = 0; i < model.meshes.size(); ++i) model.meshes[i].name = "mesh_" + std::to_string(i);
  for (size_t i = 0; i < model.nodes.size(); ++i) model.nodes[i].name = "node_" + std::to_string(i);
  for (size_t i = 0; i < model.materials.size(); ++i) model.materials[i].name = "material_" + std::to_string(i);
  return model;
}

TEST(ProceduralEyes, UnnamedEyeballsAreThePairOfBallsInTheHead) {
  const eng::Model named = plasterHead();
  const eng::Model model = withoutNames(named);
  const std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(model);
  ASSERT_EQ(eyes.size(), 2u);
  const std::vector<importers::EyePrimitive> byName = importers::findUntexturedEyes(named);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(eyes[i].mesh, byName[i].mesh);
    EXPECT_NEAR(eyes[i].radius, 1.0f, 0.02f);
    EXPECT_NEAR(eyes[i].gazeAxis.z, 1.0f, 1e-4f);
  }
  const importers::FaceDressing plan = importers::planFaceDressing(model);
  EXPECT_EQ(plan.eyes, 2u);
  EXPECT_EQ(plan.skin, 1u) << "a face, so its skin is dressed too";
}

TEST(ProceduralEyes, BallsThatAreNoPairOfEyesAreLeftAlone) {
  eng::Model oneEye = withoutNames(plasterHead());
  oneEye.nodes[2].mesh = -1;
  EXPECT_TRUE(importers::findUntexturedEyes(oneEye).empty()) << "one ball";
  eng::Model farApart = withoutNames(plasterHead());
  farApart.nodes[1].translation.x = 3.0f;
  EXPECT_TRUE(importers::findUntexturedEyes(farApart).empty()) << "too far apart";
  eng::Model uneven = withoutNames(plasterHead());
  uneven.nodes[1].translation.y += 0.1f;
  EXPECT_TRUE(importers::findUntexturedEyes(uneven).empty()) << "not level";
  eng::Model unequal = withoutNames(plasterHead());
  unequal.nodes[1].scale = glm::vec3(0.08f);
  EXPECT_TRUE(importers::findUntexturedEyes(unequal).empty()) << "not of one size";
  eng::Model noHead = withoutNames(plasterHead());
  noHead.nodes[0].mesh = noHead.nodes[3].mesh = -1;
  EXPECT_TRUE(importers::findUntexturedEyes(noHead).empty()) << "two balls in no head";
}

TEST(ProceduralEyes, TexturedEyesAndBrowsAreLeftAlone) {
  eng::Model model = plasterHead();
  model.nodes[1].name = "eyeBrowLeft";  // not a ball, whatever its shape
  model.images.push_back(importers::proceduralEyeImage(8));
  model.materials[size_t(model.meshes[2].primitives[0].material)].baseColorImage = 0;  // textured
  EXPECT_TRUE(importers::findUntexturedEyes(model).empty());
}

TEST(ProceduralEyes, ImageHasWhiteScleraDarkPupilAndColouredIris) {
  const eng::Image eye = importers::proceduralEyeImage(128);
  auto at = [&](int x, int y) { return &eye.rgba8[(size_t(y) * 128 + size_t(x)) * 4]; };
  const uint8_t* pupil = at(64, 64);
  const uint8_t* iris = at(64 + 22, 64);  // between the pupil (rho .18) and the limbus (.47)
  const uint8_t* sclera = at(64 + 45, 64);
  EXPECT_LT(pupil[0] + pupil[1] + pupil[2], 60);
  EXPECT_GT(sclera[0] + sclera[1] + sclera[2], 600);
  EXPECT_GT(iris[0], iris[2]) << "a brown iris: more red than blue";
  EXPECT_LT(iris[0] + iris[1] + iris[2], sclera[0] + sclera[1] + sclera[2]);
}

TEST(FaceDressing, PlasterHeadGetsEyesTeethSkinAndOcclusion) {
  eng::Model model = plasterHead();
  const importers::FaceDressing plan = importers::planFaceDressing(model);
  EXPECT_EQ(plan.eyes, 2u);
  EXPECT_EQ(plan.mouth, 1u);
  EXPECT_EQ(plan.skin, 1u);
  const size_t images = model.images.size();
  const importers::FaceDressing done = importers::dressUntexturedFace(model);
  EXPECT_EQ(done.total(), plan.total());
  EXPECT_EQ(model.images.size(), images + 2) << "one eye texture for both eyes, one painted skin";
  const eng::Primitive& eye = model.meshes[1].primitives[0];
  EXPECT_EQ(eye.texcoords.size(), eye.positions.size());
  EXPECT_EQ(model.materials[size_t(eye.material)].baseColorImage, int(images));
  const eng::Primitive& skin = model.meshes[0].primitives[0];
  const eng::Material& skinMaterial = model.materials[size_t(skin.material)];
  ASSERT_EQ(skinMaterial.baseColorImage, int(images) + 1) << "the skin tone and brows, painted through its UVs";
  const eng::Image& painted = model.images[size_t(skinMaterial.baseColorImage)];
  size_t toned = 0, dark = 0;
  for (size_t i = 0; i < painted.rgba8.size(); i += 4) {
    const uint8_t* t = &painted.rgba8[i];
    if (t[0] > t[1] && t[1] > t[2] && t[0] < 230) ++toned;  // skin: warm, not plaster white
    if (t[0] + t[1] + t[2] < 350) ++dark;                    // brow (skin sums ~530)
  }
  EXPECT_GT(toned, painted.rgba8.size() / 4 * 8 / 10) << "mostly skin";
  EXPECT_GT(dark, 0u) << "and brows";
  EXPECT_EQ(skin.colors.size(), skin.positions.size()) << "occlusion baked into vertex colours";
}

TEST(FaceDressing, SkinWithoutUvsKeepsAPlainSkinMaterialBesideAPaintedOne) {
  eng::Model model = plasterHead();
  eng::Primitive noUvs = model.meshes[0].primitives[0];  // same material, no texture coordinates
  noUvs.texcoords.clear();
  model.meshes[0].primitives.push_back(noUvs);
  importers::dressUntexturedFace(model);
  const eng::Material& painted = model.materials[size_t(model.meshes[0].primitives[0].material)];
  const eng::Primitive& plain = model.meshes[0].primitives[1];
  const eng::Material& plainMaterial = model.materials[size_t(plain.material)];
  EXPECT_GE(painted.baseColorImage, 0) << "the primitive with UVs samples the painted texture";
  EXPECT_EQ(plainMaterial.baseColorImage, -1) << "the one without samples nothing";
  EXPECT_GT(plainMaterial.baseColorFactor.r, plainMaterial.baseColorFactor.b) << "skin tone";
  EXPECT_LT(plainMaterial.baseColorFactor.r, 0.9f);
  const bool hasBrow = std::any_of(plain.colors.begin(), plain.colors.end(),
                                   [](const glm::vec4& c) { return c.r < 0.5f; });
  EXPECT_TRUE(hasBrow) << "its brows are in the vertex colours";
}

TEST(FaceDressing, EyeballPrimitivesOfTheFaceMeshAreKnownByTheirMaterial) {
  // One mesh (skin plus two balls, as CANDIDE-3 is imported): the skin's targets are the mesh's, so only
  // the material's name tells a ball from the skin.
  eng::Model model = plasterHead();
  for (int side : {1, 2}) {
    eng::Primitive ball = model.meshes[size_t(side)].primitives[0];
    for (glm::vec3& p : ball.positions) p = model.nodes[size_t(side)].translation + p * model.nodes[size_t(side)].scale;
    ball.targets = model.meshes[0].primitives[0].targets;
    for (eng::MorphTarget& t : ball.targets) t.positions.assign(ball.positions.size(), glm::vec3(0.0f));
    for (eng::MorphTarget& t : ball.targets) t.normals.assign(ball.positions.size(), glm::vec3(0.0f));
    ball.material = int(model.materials.size());
    eng::Material white;
    white.name = side == 1 ? "Eye_L" : "eye.R";
    model.materials.push_back(white);
    model.meshes[0].primitives.push_back(ball);
  }
  model.nodes[1].mesh = model.nodes[2].mesh = -1;  // the separate eyeballs are gone
  const importers::FaceDressing plan = importers::planFaceDressing(model);
  EXPECT_EQ(plan.eyes, 2u);
  EXPECT_EQ(plan.skin, 1u) << "the balls are not skin";
  importers::dressUntexturedFace(model);
  const int eyeImage = model.materials[size_t(model.meshes[0].primitives[1].material)].baseColorImage;
  EXPECT_GE(eyeImage, 0);
  EXPECT_EQ(model.materials[size_t(model.meshes[0].primitives[2].material)].baseColorImage, eyeImage);
  EXPECT_NE(model.materials[size_t(model.meshes[0].primitives[0].material)].baseColorImage, eyeImage);
}

TEST(PaintedBrows, BrowsSitOnTheBrowRidgeAboveEachEye) {
  const eng::Model model = plasterHead();
  const std::vector<importers::BrowFrame> frames = importers::browFrames(model, importers::findUntexturedEyes(model), 0);
  ASSERT_EQ(frames.size(), 2u);
  // Eyes at (+-0.35, 0.2, 0.85): 0.7 apart, so the brows run ~0.16 above them.
  auto onHead = [](float x, float y) { return glm::vec3(x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y))); };
  for (float side : {1.0f, -1.0f}) {
    EXPECT_GT(importers::browCoverage(frames, onHead(side * 0.37f, 0.2f + 0.19f)), 0.7f) << "above the eye";
    EXPECT_EQ(importers::browCoverage(frames, onHead(side * 0.35f, 0.2f)), 0.0f) << "not on the eye";
    EXPECT_EQ(importers::browCoverage(frames, onHead(side * 0.35f, 0.55f)), 0.0f) << "not on the forehead";
  }
  EXPECT_EQ(importers::browCoverage(frames, onHead(0.0f, 0.37f)), 0.0f) << "the glabella stays bare";
  EXPECT_EQ(importers::browCoverage(frames, glm::vec3(0.37f, 0.39f, -0.83f)), 0.0f) << "nothing on the back of the head";
}

TEST(PaintedBrowsValidity, NoBrowsWithoutExactlyTwoEyes) {
  const eng::Model model = plasterHead();
  std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(model);
  eyes.pop_back();
  EXPECT_TRUE(importers::browFrames(model, eyes, 0).empty());
  eyes.clear();
  EXPECT_TRUE(importers::browFrames(model, eyes, 0).empty());
  std::vector<importers::EyePrimitive> sameSpot = importers::findUntexturedEyes(model);
  sameSpot[1] = sameSpot[0];  // two eyes in one place: no across axis
  EXPECT_TRUE(importers::browFrames(model, sameSpot, 0).empty());
}

// An exporter's default for a material nobody coloured is no colour either:
// Blender writes its base colour 0.8 (glTF baseColorFactor, OBJ Kd), Maya's
// lambert1 is 0.5. A tinted or dark skin or mouth is the author's.
TEST(FaceDressing, AnExportersDefaultGreyIsDressedAsWhiteIs) {
  const importers::FaceDressing white = importers::planFaceDressing(plasterHead());
  ASSERT_EQ(white.eyes, 2u);
  for (float grey : {0.8f, 0.5f}) {
    eng::Model model = plasterHead();
    for (eng::Material& m : model.materials) m.baseColorFactor = glm::vec4(grey, grey, grey, 1.0f);
    const importers::FaceDressing plan = importers::planFaceDressing(model);
    EXPECT_EQ(plan.eyes, white.eyes) << grey;
    EXPECT_EQ(plan.mouth, white.mouth) << grey;
    EXPECT_EQ(plan.skin, white.skin) << grey;
  }
  for (const glm::vec4& authored : {glm::vec4(0.3f, 0.3f, 0.3f, 1.0f), glm::vec4(0.8f, 0.78f, 0.8f, 1.0f)}) {
    eng::Model model = plasterHead();
    for (eng::Material& m : model.materials) m.baseColorFactor = authored;
    EXPECT_EQ(importers::planFaceDressing(model).skin, 0u) << authored.r << " " << authored.g;
    EXPECT_EQ(importers::planFaceDressing(model).mouth, 0u) << authored.r << " " << authored.g;
  }
}

TEST(FaceDressing, NonFaceModelsAndAuthoredColoursStayAsAuthored) {
  eng::Model sphere = makeSphereModel(whiteSphereSpec(2));  // a morphing sample, no eyes, not named a face
  EXPECT_EQ(importers::planFaceDressing(sphere).total(), 0u);
  eng::Model coloured = plasterHead();
  for (eng::Material& m : coloured.materials) m.baseColorFactor = glm::vec4(0.7f, 0.5f, 0.4f, 1.0f);
  EXPECT_EQ(importers::planFaceDressing(coloured).skin, 0u);
  EXPECT_EQ(importers::planFaceDressing(coloured).mouth, 0u);
  // A scan painted per vertex (COLOR_0, an OBJ's 'v x y z r g b') on white
  // materials is authored too; all-white vertex colours are no paint.
  eng::Model painted = plasterHead();
  const importers::FaceDressing plaster = importers::planFaceDressing(painted);
  ASSERT_GT(plaster.total(), 0u);
  for (eng::Mesh& mesh : painted.meshes)
    for (eng::Primitive& prim : mesh.primitives) prim.colors.assign(prim.vertexCount(), glm::vec4(1.0f));
  EXPECT_EQ(importers::planFaceDressing(painted).total(), plaster.total());
  for (eng::Mesh& mesh : painted.meshes)
    for (eng::Primitive& prim : mesh.primitives) prim.colors.assign(prim.vertexCount(), glm::vec4(0.8f, 0.6f, 0.5f, 1.0f));
  EXPECT_EQ(importers::planFaceDressing(painted).total(), 0u);
}

TEST(VertexOcclusion, InsideOfAClosedShellIsDarkOutsideIsOpen) {
  // A small ball inside a big one: the small ball sees only the big one's inside.
  eng::Model model;
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "shell", {0, 0, 0}, glm::vec3(1.0f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "core", {0, 0, 0}, glm::vec3(0.3f));
  const auto visible = importers::bakeVertexOcclusion(model, {.resolution = 64, .rays = 32, .reach = 1.0f});
  float shell = 1.0f, core = 0.0f;
  for (float v : visible[0][0]) shell = std::min(shell, v);
  for (float v : visible[1][0]) core = std::max(core, v);
  EXPECT_GT(shell, 0.8f) << "the outside of the shell sees the sky (grazing rays may touch the curve)";
  EXPECT_LT(core, 0.1f) << "the ball inside sees none";
}

}  // namespace
