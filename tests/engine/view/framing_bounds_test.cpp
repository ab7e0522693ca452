// What the face framing frames (engine/view/framing_bounds.h), on models
// built here.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/view/camera.h"
#include "engine/view/framing_bounds.h"
#include "tests/common/test_meshes.h"

namespace {

using testing_support::addPartAsRoot;
using testing_support::makeSphereModel;
using testing_support::whiteSphereSpec;

TEST(FaceFraming, FullBodyIsFramedAtItsHead) {
  // A tall body without targets and a head whose targets move it: the face
  // framing is the head and neck, not the body.
  eng::Model model;
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "body", {0, 0.8f, 0}, glm::vec3(0.3f, 0.8f, 0.2f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(2)), "head", {0, 1.75f, 0}, glm::vec3(0.11f));
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

// A head without targets standing on a floor 60 units wide: the face
// framing leaves the floor out (a flat part), so the landmark finder's first
// view shows a face, not a speck; with nothing but flat parts it keeps them.
TEST(FaceFraming, AFaceWithoutTargetsIsFramedWithoutItsFloor) {
  eng::Model model;
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "head", {0, 1.7f, 0}, glm::vec3(0.1f, 0.12f, 0.11f));
  const eng::Aabb alone = eng::framingBounds(model, eng::FramingMode::Face);
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "floor", {0, 0, 0}, glm::vec3(30.0f, 0.001f, 30.0f));
  const eng::Aabb face = eng::framingBounds(model, eng::FramingMode::Face);
  ASSERT_TRUE(face.valid());
  EXPECT_NEAR(face.size().x, alone.size().x, 1e-4f);
  EXPECT_NEAR(face.center().y, 1.7f, 1e-3f);
  EXPECT_GT(eng::framingBounds(model, eng::FramingMode::All).size().x, 50.0f) << "all of it: the floor too";
  eng::Model floorOnly;
  addPartAsRoot(floorOnly, makeSphereModel(whiteSphereSpec(0)), "floor", {0, 0, 0}, glm::vec3(30.0f, 0.001f, 30.0f));
  EXPECT_GT(eng::framingBounds(floorOnly, eng::FramingMode::Face).size().x, 50.0f);
}

// A skinned figure: a neck joint at y 1.5 and the head joint above it at
// 1.6; a head (a box to the crown at 1.85), a body under the neck, and, when
// `hairTo` is below the chin, a lock of hair skinned to the head reaching it.
eng::Model skinnedFigure(float hairTo) {
  eng::Model model;
  model.nodes.resize(3);
  model.nodes[0].name = "Armature";
  model.nodes[0].children = {1, 2};
  model.nodes[0].mesh = 0;
  model.nodes[0].skin = 0;
  model.nodes[1].name = "Neck";
  model.nodes[1].parent = 0;
  model.nodes[1].translation = {0, 1.5f, 0};
  model.nodes[2].name = "Head";
  model.nodes[2].parent = 0;
  model.nodes[2].translation = {0, 1.6f, 0};
  model.roots = {0};
  model.skins.push_back({"skin", {1, 2}, {glm::translate(glm::mat4(1.0f), {0, -1.5f, 0}),
                                          glm::translate(glm::mat4(1.0f), {0, -1.6f, 0})}});
  eng::Primitive prim;
  auto add = [&](glm::vec3 p, int joint) {
    prim.positions.push_back(p);
    prim.normals.push_back({0, 0, 1});
    prim.joints.push_back(glm::u16vec4(uint16_t(joint), 0, 0, 0));
    prim.jointWeights.push_back({1, 0, 0, 0});
  };
  for (glm::vec3 p : {glm::vec3(-0.08f, 1.6f, 0.1f), glm::vec3(0.08f, 1.6f, 0.1f), glm::vec3(0, 1.85f, 0.0f),
                      glm::vec3(0, 1.7f, 0.12f)})
    add(p, 1);  // the head (joint slot 1: Head)
  for (glm::vec3 p : {glm::vec3(-0.2f, 0.9f, 0.0f), glm::vec3(0.2f, 1.45f, 0.0f), glm::vec3(0, 1.2f, 0.1f)})
    add(p, 0);  // the body (slot 0: Neck)
  add({0.1f, hairTo, -0.05f}, 1);
  add({-0.1f, hairTo, -0.05f}, 1);
  prim.indices = {0, 1, 3, 1, 2, 3, 4, 5, 6, 7, 8, 2};
  // The face's target moves the front of the head (the mouth).
  eng::MorphTarget target;
  target.positions.assign(prim.positions.size(), glm::vec3(0.0f));
  target.positions[3] = {0, -0.02f, 0};
  target.positions[0] = {0, -0.01f, 0};
  prim.targets.push_back(target);
  eng::Mesh mesh;
  mesh.name = "figure";
  mesh.targetNames = {"mouthOpen"};
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  return model;
}

TEST(FaceFraming, LongHairSkinnedToTheHeadDoesNotWidenTheFaceView) {
  // Short hair: the head and its neck, not the body.
  const eng::Aabb cropped = eng::framingBounds(skinnedFigure(1.65f), eng::FramingMode::Face);
  ASSERT_TRUE(cropped.valid());
  EXPECT_NEAR(cropped.max.y, 1.85f + 0.05f * 0.25f, 1e-4f);
  EXPECT_NEAR(cropped.min.y, 1.6f - 0.3f * 0.25f, 1e-4f) << "the neck below the head's lowest vertex";
  // Hair down to the waist moves with the head joint; the face view still
  // reaches only the neck.
  const eng::Aabb longHair = eng::framingBounds(skinnedFigure(1.0f), eng::FramingMode::Face);
  ASSERT_TRUE(longHair.valid());
  const float chin = 1.6f - 0.45f * (1.85f - 1.6f), height = 1.85f - chin;
  EXPECT_NEAR(longHair.max.y, 1.85f + 0.05f * height, 1e-4f);
  EXPECT_NEAR(longHair.min.y, chin - 0.3f * height, 1e-4f);
  EXPECT_LT(longHair.size().y, 0.5f);
  EXPECT_GT(eng::framingBounds(skinnedFigure(1.0f), eng::FramingMode::All).size().y, 0.9f);
}

TEST(FaceFraming, ModelWithoutTargetsFallsBackToTheWholeModel) {
  eng::Model model = makeSphereModel(whiteSphereSpec(0));
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
