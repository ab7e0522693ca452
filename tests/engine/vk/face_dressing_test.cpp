// How untextured faces are shown (importers/face_dressing.h,
// procedural_eyes.h, vertex_occlusion.h), which parts sit inside the head
// (engine/scene/inner_face_parts.h) and what the face framing frames
// (engine/view/framing_bounds.h), on models built here.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/inner_face_parts.h"
#include "importers/face_dressing.h"
#include "importers/painted_brows.h"
#include "importers/procedural_eyes.h"
#include "importers/vertex_occlusion.h"
#include "engine/view/camera.h"
#include "engine/view/framing_bounds.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/test_models.h"

namespace {

// Adds `part` (one sphere model) to `model` as a root node `name` at `at`, scaled by `scale`.
void addPart(eng::Model& model, eng::Model part, const std::string& name, glm::vec3 at, glm::vec3 scale) {
  const int mesh = int(model.meshes.size());
  for (eng::Primitive& prim : part.meshes[0].primitives)
    if (prim.material >= 0) prim.material += int(model.materials.size());
  for (eng::Material& m : part.materials) model.materials.push_back(m);
  model.meshes.push_back(std::move(part.meshes[0]));
  eng::Node node;
  node.name = name;
  node.mesh = mesh;
  node.translation = at;
  node.scale = scale;
  model.roots.push_back(int(model.nodes.size()));
  model.nodes.push_back(node);
}

vk_test::SphereSpec whiteSphere(int targets) {
  vk_test::SphereSpec spec;
  spec.targets = targets;
  spec.color = glm::vec4(1.0f);
  return spec;
}

// A plaster head: a sphere with targets, two untextured eyeballs, teeth.
eng::Model plasterHead() {
  eng::Model model;
  addPart(model, vk_test::makeSphereModel(whiteSphere(2)), "head", {0, 0, 0}, glm::vec3(1.0f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "eyeLeft", {0.35f, 0.2f, 0.85f}, glm::vec3(0.12f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "eyeRight", {-0.35f, 0.2f, 0.85f}, glm::vec3(0.12f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "teeth", {0, -0.4f, 0.8f}, glm::vec3(0.2f, 0.05f, 0.1f));
  return model;
}

TEST(ProceduralEyes, UntexturedEyeballsAreFoundByNameAndShape) {
  const eng::Model model = plasterHead();
  const std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(model);
  ASSERT_EQ(eyes.size(), 2u);
  for (const importers::EyePrimitive& eye : eyes) {
    EXPECT_NEAR(eye.radius, 1.0f, 0.02f) << "sphere fit in mesh space";
    EXPECT_NEAR(eye.gazeAxis.z, 1.0f, 1e-4f) << "the face looks along +Z";
  }
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

TEST(FaceDressing, EyesAndTeethInsideTheHeadAreFoundByNameAndBounds) {
  eng::Model model = plasterHead();
  // An ear named like nothing inside, and "teeth" hanging outside the head.
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "ear", {0.9f, 0, 0}, glm::vec3(0.05f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "teeth necklace", {0, -1.5f, 0}, glm::vec3(0.2f));
  const std::vector<std::vector<bool>> inside = eng::partsInsideTheHead(model);
  ASSERT_EQ(inside.size(), model.meshes.size());
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const std::string& name = model.nodes[size_t(nodeOfMesh[m])].name;
    const bool expected = name == "eyeLeft" || name == "eyeRight" || name == "teeth";
    ASSERT_EQ(inside[m].size(), model.meshes[m].primitives.size());
    for (bool flag : inside[m]) EXPECT_EQ(flag, expected) << name;
  }
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

TEST(FaceDressing, NonFaceModelsAndAuthoredColoursStayAsAuthored) {
  eng::Model sphere = vk_test::makeSphereModel(whiteSphere(2));  // a morphing sample, no eyes, not named a face
  EXPECT_EQ(importers::planFaceDressing(sphere).total(), 0u);
  eng::Model coloured = plasterHead();
  for (eng::Material& m : coloured.materials) m.baseColorFactor = glm::vec4(0.7f, 0.5f, 0.4f, 1.0f);
  EXPECT_EQ(importers::planFaceDressing(coloured).skin, 0u);
  EXPECT_EQ(importers::planFaceDressing(coloured).mouth, 0u);
}

TEST(VertexOcclusion, InsideOfAClosedShellIsDarkOutsideIsOpen) {
  // A small ball inside a big one: the small ball sees only the big one's inside.
  eng::Model model;
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "shell", {0, 0, 0}, glm::vec3(1.0f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "core", {0, 0, 0}, glm::vec3(0.3f));
  const auto visible = importers::bakeVertexOcclusion(model, {.resolution = 64, .rays = 32, .reach = 1.0f});
  float shell = 1.0f, core = 0.0f;
  for (float v : visible[0][0]) shell = std::min(shell, v);
  for (float v : visible[1][0]) core = std::max(core, v);
  EXPECT_GT(shell, 0.8f) << "the outside of the shell sees the sky (grazing rays may touch the curve)";
  EXPECT_LT(core, 0.1f) << "the ball inside sees none";
}

TEST(FaceFraming, FullBodyIsFramedAtItsHead) {
  // A tall body without targets and a head whose targets move it: the face
  // framing is the head and neck, not the body.
  eng::Model model;
  addPart(model, vk_test::makeSphereModel(whiteSphere(0)), "body", {0, 0.8f, 0}, glm::vec3(0.3f, 0.8f, 0.2f));
  addPart(model, vk_test::makeSphereModel(whiteSphere(2)), "head", {0, 1.75f, 0}, glm::vec3(0.11f));
  const eng::Aabb all = eng::framingBounds(model, eng::FramingMode::All);
  const eng::Aabb face = eng::framingBounds(model, eng::FramingMode::Face);
  ASSERT_TRUE(face.valid());
  EXPECT_GT(all.size().y, 1.5f);
  EXPECT_LT(face.size().y, 0.6f) << "head and neck, not the body";
  EXPECT_NEAR(face.max.y, 1.75f + 0.11f * 1.3f, 0.1f) << "the top of the head (and its bumps) is in";
  EXPECT_LT(face.min.y, 1.75f - 0.11f) << "the neck below the chin is in";
  const eng::Aabb moved = eng::morphedRegionBounds(model);
  EXPECT_NEAR(moved.center().y, 1.75f, 0.05f);
}

TEST(FaceFraming, ModelWithoutTargetsFallsBackToTheWholeModel) {
  eng::Model model = vk_test::makeSphereModel(whiteSphere(0));
  const eng::Aabb all = eng::framingBounds(model, eng::FramingMode::All);
  const eng::Aabb face = eng::framingBounds(model, eng::FramingMode::Face);
  EXPECT_EQ(face.min, all.min);
  EXPECT_EQ(face.max, all.max);
  EXPECT_EQ(eng::framingModeFromName("face"), eng::FramingMode::Face);
  EXPECT_EQ(eng::framingModeFromName("all"), eng::FramingMode::All);
  EXPECT_FALSE(eng::framingModeFromName("body"));
}

TEST(FaceFraming, FeatureBoundsKeepWhatTargetsCarryNotTheSkinTheyDrag) {
  // One target lifts two vertices by 1 (the feature) and nudges two others
  // by 0.05 (skin dragged along): the features are the first two.
  eng::Mesh mesh;
  eng::Primitive prim;
  prim.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 3, 0}};
  prim.indices = {0, 1, 2, 0, 2, 3, 3, 2, 4};
  eng::MorphTarget lift;
  lift.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0.05f, 0}, {0, 0.05f, 0}, {0, 0, 0}};
  lift.positions[0] = {0, 1, 0};
  lift.positions[1] = {0, 1, 0};
  prim.targets.push_back(lift);
  mesh.primitives.push_back(prim);
  mesh.targetNames = {"lift"};
  mesh.defaultWeights = {0.0f};
  eng::Model model = testing_support::singleMeshModel(std::move(mesh));
  const eng::Aabb features = eng::faceFeatureBounds(model);
  ASSERT_TRUE(features.valid());
  EXPECT_FLOAT_EQ(features.min.y, -1.0f);
  EXPECT_FLOAT_EQ(features.max.y, -1.0f) << "the dragged vertices at y = 1 are not features";
  EXPECT_FLOAT_EQ(features.min.x, -1.0f);
  EXPECT_FLOAT_EQ(features.max.x, 1.0f);
  model.meshes[0].primitives[0].targets.clear();
  model.meshes[0].targetNames.clear();
  model.meshes[0].defaultWeights.clear();
  EXPECT_FALSE(eng::faceFeatureBounds(model).valid()) << "nothing morphs";
}

// Whether every corner of `box` projects inside the image of `camera`.
bool inView(const eng::OrbitCamera& camera, const eng::Aabb& box) {
  const glm::mat4 viewProj = camera.projection(1.0f) * camera.view();
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z);
    const glm::vec4 clip = viewProj * glm::vec4(corner, 1.0f);
    if (std::abs(clip.x / clip.w) > 1.0f || std::abs(clip.y / clip.w) > 1.0f) return false;
  }
  return true;
}

TEST(FaceFraming, ZoomStopsWhereTheFeaturesWouldLeaveTheImage) {
  const eng::Aabb head{{-1, -1, -1}, {1, 1, 1}};
  // Small features at the centre: the wanted zoom stands.
  EXPECT_FLOAT_EQ(eng::zoomShowing(head, {{-0.2f, -0.2f, 0}, {0.2f, 0.2f, 0.5f}}, 1.4f, 1.0f), 1.4f);
  // Features filling the head: no zoom past the head's own framing.
  EXPECT_FLOAT_EQ(eng::zoomShowing(head, head, 1.4f, 1.0f), 1.0f);
  // Features reaching the top and the sides (a robot's eyes and brows): zoom
  // in only as far as keeps them whole; a little further would cut them.
  const eng::Aabb features{{-0.85f, -0.2f, 0.0f}, {0.85f, 0.9f, 0.9f}};
  const float zoom = eng::zoomShowing(head, features, 1.4f, 1.0f);
  EXPECT_GT(zoom, 1.0f);
  EXPECT_LT(zoom, 1.4f);
  eng::OrbitCamera camera = eng::OrbitCamera::frame(head, 1.0f);
  camera.zoom = zoom;
  EXPECT_TRUE(inView(camera, features));
  camera.zoom = zoom * 1.1f;
  EXPECT_FALSE(inView(camera, features));
  // Nothing to keep in view, or no zoom asked: as asked.
  EXPECT_FLOAT_EQ(eng::zoomShowing(head, eng::Aabb{}, 1.4f, 1.0f), 1.4f);
  EXPECT_FLOAT_EQ(eng::zoomShowing(head, features, 0.8f, 1.0f), 0.8f);
}

}  // namespace
