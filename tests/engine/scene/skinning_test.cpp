// Skinning on the CPU side: JOINTS_n / WEIGHTS_n of every component type glTF
// allows, skins, skeletal animation channels (STEP / LINEAR / CUBICSPLINE),
// poses, the CPU reference (morph then skin), posed bounds and the head joint.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/skinning.h"
#include "engine/scene/weights.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/skin_test_files.h"

namespace {

using namespace scene_test;
using testing_support::freshTempDir;

eng::Model loadStrip(const SkinnedStripSpec& spec, const std::string& name) {
  const auto dir = freshTempDir("skinning_" + name);
  skinnedStrip(spec).writeGlb(dir / "strip.glb");
  auto model = eng::loadModel(dir / "strip.glb");
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  return model.ok() ? std::move(*model) : eng::Model{};
}

// The strip's vertices, morphed and skinned in `pose`, in world space.
std::vector<glm::vec3> posedVertices(const eng::Model& model, const eng::Pose& pose) {
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, pose, world);
  const eng::Primitive& prim = model.meshes.at(0).primitives.at(0);
  std::vector<glm::vec3> positions(prim.vertexCount()), normals(prim.vertexCount());
  eng::posePrimitiveCpu(model, 0, prim, {}, world, positions, normals);
  for (glm::vec3& p : positions) p = glm::vec3(world[0] * glm::vec4(p, 1.0f));
  return positions;
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
  EXPECT_LE(glm::length(a - b), tolerance) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", "
                                           << b.y << ", " << b.z << ")";
}

// Two vertices, one influence group each, both fully on joint 0.
eng::Primitive twoSkinnedVertices() {
  eng::Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}};
  p.normals = {{0, 0, 1}, {0, 0, 1}};
  p.joints = {glm::u16vec4(0), glm::u16vec4(0)};
  p.jointWeights = {glm::vec4(1, 0, 0, 0), glm::vec4(1, 0, 0, 0)};
  return p;
}

TEST(SkinningValidity, MismatchedSpansAreRefusedAndTouchNothing) {
  const eng::Primitive p = twoSkinnedVertices();
  const glm::mat4 lift = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
  std::vector<glm::vec3> shortPositions(1, glm::vec3(7.0f)), positions(2, glm::vec3(7.0f)), shortNormals(1);
  const eng::SkinPrimitiveJob tooShort{&p, {&lift, 1}, shortPositions, {}};
  ASSERT_FALSE(tooShort.Validate());
  EXPECT_EQ(tooShort.Validate().error().kind, eng::ErrorKind::InvalidArgument);
  EXPECT_EQ(tooShort.Validate().error().message, "SkinPrimitiveJob: positions has 1 entries, primitive has 2 vertices");
  EXPECT_FALSE(tooShort.Run());
  EXPECT_EQ(shortPositions[0], glm::vec3(7.0f));
  const eng::SkinPrimitiveJob badNormals{&p, {&lift, 1}, positions, shortNormals};
  ASSERT_FALSE(badNormals.Validate());
  EXPECT_EQ(badNormals.Validate().error().message, "SkinPrimitiveJob: normals has 1 entries, primitive has 2 vertices");
  EXPECT_FALSE(eng::skinPrimitiveCpu(p, {&lift, 1}, positions, shortNormals));
  EXPECT_EQ(positions[1], glm::vec3(7.0f));
  ASSERT_FALSE(eng::SkinPrimitiveJob{}.Validate());
  EXPECT_EQ(eng::SkinPrimitiveJob{}.Validate().error().message, "SkinPrimitiveJob: no primitive");
}

TEST(SkinningValidity, InfluenceGroupsMustCoverEveryVertex) {
  eng::Primitive p = twoSkinnedVertices();
  p.jointWeights.pop_back();
  std::vector<glm::vec3> positions(2);
  const eng::SkinPrimitiveJob job{&p, {}, positions, {}};
  ASSERT_FALSE(job.Validate());
  EXPECT_EQ(job.Validate().error().message, "SkinPrimitiveJob: primitive has 2 joint groups and 1 weight groups for 2 vertices");
}

TEST(SkinningValidity, AValidJobSkins) {
  const eng::Primitive p = twoSkinnedVertices();
  const glm::mat4 lift = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
  std::vector<glm::vec3> positions = p.positions;
  const eng::SkinPrimitiveJob job{&p, {&lift, 1}, positions, {}};
  EXPECT_TRUE(job.Validate());
  ASSERT_TRUE(job.Run());
  expectNear(positions[1], {1, 1, 0});
}

TEST(SkinningValidity, PosingRefusesWrongWeightsBeforeWriting) {
  eng::Model model;
  model.nodes.resize(1);
  const eng::Primitive p = twoSkinnedVertices();
  const std::vector<glm::mat4> world(1, glm::mat4(1.0f));
  std::vector<glm::vec3> positions(2, glm::vec3(7.0f));
  const float oneWeightTooMany[] = {1.0f};
  EXPECT_FALSE(eng::posePrimitiveCpu(model, 0, p, oneWeightTooMany, world, positions, {}));
  EXPECT_EQ(positions[0], glm::vec3(7.0f));
  EXPECT_TRUE(eng::posePrimitiveCpu(model, 0, p, {}, world, positions, {}));
  expectNear(positions[1], {1, 0, 0});
}

TEST(Skinning, LoadsJointsWeightsSkinAndChannels) {
  const eng::Model model = loadStrip({}, "basic");
  ASSERT_EQ(model.skins.size(), 1u);
  const eng::Skin& skin = model.skins[0];
  EXPECT_EQ(skin.name, "Armature");
  EXPECT_EQ(skin.joints, (std::vector<int>{1, 2}));
  EXPECT_EQ(skin.skeleton, 1);
  ASSERT_EQ(skin.inverseBindMatrices.size(), 2u);
  EXPECT_EQ(skin.inverseBindMatrices[1][3], glm::vec4(-1, 0, 0, 1));
  EXPECT_EQ(model.nodes[0].skin, 0);
  EXPECT_EQ(model.nodes[1].skin, -1);
  EXPECT_EQ(model.nodes[2].parent, 1);
  const eng::Primitive& prim = model.meshes[0].primitives[0];
  EXPECT_EQ(prim.influenceSets(), 1u);
  EXPECT_EQ(prim.joints[4], glm::u16vec4(0, 1, 0, 0));
  EXPECT_EQ(prim.jointWeights[2], glm::vec4(0.5f, 0.5f, 0, 0));
  ASSERT_EQ(model.animations.size(), 1u);
  const eng::Animation& anim = model.animations[0];
  EXPECT_EQ(anim.otherChannelCount, 1u);
  ASSERT_EQ(anim.nodeChannels.size(), 1u);
  EXPECT_EQ(anim.nodeChannels[0].node, 2);
  EXPECT_EQ(anim.nodeChannels[0].path, eng::NodePath::Rotation);
  EXPECT_EQ(anim.nodeChannels[0].values.size(), 8u);
  EXPECT_FLOAT_EQ(anim.duration(), 1.0f);
  EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
}

TEST(Skinning, EveryJointAndWeightComponentTypeLoadsTheSameInfluences) {
  const eng::Model reference = loadStrip({}, "float");
  for (int jointType : {kUnsignedByte, kUnsignedShort})
    for (int weightType : {kFloat, kUnsignedByte, kUnsignedShort})
      for (bool twoSets : {false, true}) {
        SCOPED_TRACE("joints " + std::to_string(jointType) + " weights " + std::to_string(weightType) +
                     (twoSets ? " two sets" : ""));
        const eng::Model model =
            loadStrip({.jointType = jointType, .weightType = weightType, .secondInfluenceSet = twoSets},
                      "types_" + std::to_string(jointType) + "_" + std::to_string(weightType) + (twoSets ? "_2" : ""));
        const eng::Primitive& prim = model.meshes.at(0).primitives.at(0);
        ASSERT_EQ(prim.influenceSets(), twoSets ? 2u : 1u);
        for (size_t v = 0; v < prim.vertexCount(); ++v) {
          float sum = 0.0f;
          for (size_t s = 0; s < prim.influenceSets(); ++s) {
            const glm::vec4 w = prim.jointWeights[v * prim.influenceSets() + s];
            sum += w.x + w.y + w.z + w.w;
          }
          EXPECT_NEAR(sum, 1.0f, 1e-6f) << "vertex " << v;
        }
        eng::Pose pose = eng::restPose(model);
        eng::sampleAnimation(model.animations.at(0), 0.7f, pose);
        eng::Pose referencePose = eng::restPose(reference);
        eng::sampleAnimation(reference.animations.at(0), 0.7f, referencePose);
        const auto got = posedVertices(model, pose), want = posedVertices(reference, referencePose);
        for (size_t v = 0; v < got.size(); ++v) expectNear(got[v], want[v], 2e-3f);
      }
}

TEST(Skinning, RestPoseLeavesTheMeshWhereItIs) {
  const eng::Model model = loadStrip({}, "rest");
  const auto posed = posedVertices(model, eng::restPose(model));
  const eng::Primitive& prim = model.meshes[0].primitives[0];
  for (size_t v = 0; v < posed.size(); ++v) expectNear(posed[v], prim.positions[v]);
  const eng::Aabb posedBox = eng::posedBounds(model, eng::restPose(model));
  expectNear(posedBox.min, model.bounds().min);
  expectNear(posedBox.max, model.bounds().max);
}

TEST(Skinning, LinearRotationBendsTheStrip) {
  const eng::Model model = loadStrip({}, "linear");
  eng::Pose pose = eng::restPose(model);
  eng::sampleAnimation(model.animations[0], 1.0f, pose);
  auto v = posedVertices(model, pose);
  expectNear(v[0], {0, 0, 0});
  expectNear(v[2], {1, 0, 0});
  expectNear(v[3], {0.5f, 0.5f, 0});  // half Hips (1,1), half Head (0,0)
  expectNear(v[4], {1, 1, 0});
  expectNear(v[5], {0, 1, 0});
  eng::sampleAnimation(model.animations[0], 0.5f, pose);
  v = posedVertices(model, pose);
  const float h = std::sqrt(0.5f);
  expectNear(v[4], {1 + h, h, 0});  // slerp: 45 degrees half way
  eng::sampleAnimation(model.animations[0], 7.0f, pose);  // past the end: the last key
  expectNear(posedVertices(model, pose)[4], {1, 1, 0});
}

TEST(Skinning, StepAndCubicSplineInterpolation) {
  const eng::Model step = loadStrip({.interpolation = "STEP"}, "step");
  eng::Pose pose = eng::restPose(step);
  eng::sampleAnimation(step.animations.at(0), 0.99f, pose);
  expectNear(posedVertices(step, pose)[4], {2, 0, 0});
  eng::sampleAnimation(step.animations.at(0), 1.0f, pose);
  expectNear(posedVertices(step, pose)[4], {1, 1, 0});

  const eng::Model cubic = loadStrip({.interpolation = "CUBICSPLINE"}, "cubic");
  ASSERT_EQ(cubic.animations.at(0).nodeChannels.at(0).values.size(), 24u);
  pose = eng::restPose(cubic);
  eng::sampleAnimation(cubic.animations[0], 0.5f, pose);
  // Zero tangents, half way: the normalised mean of the two keys, 45 degrees.
  const float h = std::sqrt(0.5f);
  expectNear(posedVertices(cubic, pose)[4], {1 + h, h, 0});
  eng::sampleAnimation(cubic.animations[0], 0.25f, pose);
  const float angle = 2.0f * std::acos(std::clamp(pose.rotations[2].w, -1.0f, 1.0f));
  EXPECT_GT(angle, 0.0f);
  EXPECT_LT(angle, glm::radians(45.0f));  // eases in
}

TEST(Skinning, SkinningFollowsMorphing) {
  eng::Model model = loadStrip({}, "morph");
  // A target lifting vertex 4 by +1 in Y, added by hand: morph first, then skin.
  eng::Primitive& prim = model.meshes[0].primitives[0];
  eng::MorphTarget lift;
  lift.positions.assign(prim.vertexCount(), glm::vec3(0.0f));
  lift.positions[4] = glm::vec3(0, 1, 0);
  prim.targets.push_back(lift);
  model.meshes[0].targetNames.push_back("lift");
  model.meshes[0].defaultWeights.push_back(0.0f);
  eng::Pose pose = eng::restPose(model);
  eng::sampleAnimation(model.animations[0], 1.0f, pose);
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, pose, world);
  std::vector<glm::vec3> positions(prim.vertexCount());
  const float weights[] = {1.0f};
  eng::posePrimitiveCpu(model, 0, prim, weights, world, positions, {});
  // (2,1,0) after the morph, then turned 90 degrees about the Head joint at (1,0,0).
  expectNear(positions[4], {0, 1, 0});
  const eng::Aabb box = eng::posedBounds(model, pose, weights);
  expectNear(box.min, {0, 0, 0});
  expectNear(box.max, {1, 1, 0});
}

TEST(Skinning, JointRegionBoundsKeepWhatTheJointMoves) {
  const eng::Model model = loadStrip({}, "region");
  eng::Pose pose = eng::restPose(model);
  eng::sampleAnimation(model.animations[0], 1.0f, pose);
  const eng::Aabb half = eng::posedJointRegionBounds(model, pose, 2, 0.5f);
  expectNear(half.min, {0, 0, 0});
  expectNear(half.max, {1, 1, 0});
  const eng::Aabb full = eng::posedJointRegionBounds(model, pose, 2, 0.75f);
  expectNear(full.min, {0, 1, 0});
  expectNear(full.max, {1, 1, 0});
  // Hips and everything under it: the whole strip.
  const eng::Aabb all = eng::posedJointRegionBounds(model, pose, 1, 0.99f);
  expectNear(all.min, {0, 0, 0});
  EXPECT_FALSE(eng::posedJointRegionBounds(model, pose, 99).valid());
  EXPECT_FALSE(eng::posedJointRegionBounds(model, pose, 0).valid()) << "node 0 is no joint";
}

TEST(Skinning, FindsTheHeadJointByName) {
  eng::Model model = loadStrip({}, "head");
  EXPECT_EQ(eng::findHeadJoint(model), 2);
  for (const char* name : {"head", "mixamorig:Head", "J_Bip_C_Head", "Bip01 Head", "CC_Base_Head"}) {
    model.nodes[2].name = name;
    EXPECT_EQ(eng::findHeadJoint(model), 2) << name;
  }
  for (const char* name : {"HeadTop_End", "head_end", "HeadEnd", "Forehead"}) {
    model.nodes[2].name = name;
    model.nodes[1].name = "Head";
    EXPECT_EQ(eng::findHeadJoint(model), 1) << name << " is not the head";
  }
  model.humanoidHead = 2;  // VRM humanoid bone wins over names
  EXPECT_EQ(eng::findHeadJoint(model), 2);
}

TEST(Skinning, HeadJointWithoutNamesIsTheHighestWeightedJoint) {
  eng::Model model = loadStrip({}, "head_unnamed");
  model.nodes[1].name = model.nodes[2].name = "";
  model.nodes[1].rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));  // the strip stands up
  EXPECT_EQ(eng::findHeadJoint(model), 2);
  EXPECT_EQ(eng::findHeadJoint(eng::Model{}), -1);
}

TEST(Skinning, UnskinnedModelHasNoHeadJointAndPosedBoundsAreRestBounds) {
  const auto dir = freshTempDir("skinning_unskinned");
  quadWithTarget().writeGlb(dir / "quad.glb");
  auto model = eng::loadModel(dir / "quad.glb");
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_EQ(eng::findHeadJoint(*model), -1);
  const eng::Aabb box = eng::posedBounds(*model, eng::restPose(*model));
  EXPECT_EQ(box.min, model->bounds().min);
  EXPECT_EQ(box.max, model->bounds().max);
  const std::vector<float> weights{1.0f};
  EXPECT_FLOAT_EQ(eng::posedBounds(*model, eng::restPose(*model), weights).max.z, 1.0f);
}

TEST(Skinning, SharedVrmHumanoidHeadBone) {
  FACIAL_REQUIRE_SHARED();
  for (const char* file : {"modifier_shapekey_vrm0.vrm", "modifier_shapekey_vrm1.vrm"}) {
    SCOPED_TRACE(file);
    auto model = eng::loadModel(testing_support::sharedDir() / "assets" / "vrm" / file);
    ASSERT_TRUE(model) << model.error().message;
    ASSERT_GE(model->humanoidHead, 0);
    EXPECT_EQ(model->nodes[model->humanoidHead].name, "head");
    EXPECT_EQ(eng::findHeadJoint(*model), model->humanoidHead);
  }
}

}  // namespace

namespace {

eng::Model loadShared(const std::string& relative) {
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / relative);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  return model.ok() ? std::move(*model) : eng::Model{};
}

bool isSkinJoint(const eng::Model& model, int node) {
  for (const eng::Skin& skin : model.skins)
    if (std::find(skin.joints.begin(), skin.joints.end(), node) != skin.joints.end()) return true;
  return false;
}

TEST(SkinningSharedAssets, CesiumManWalksWithNineteenJoints) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = loadShared("khronos/CesiumMan/glTF-Binary/CesiumMan.glb");
  ASSERT_EQ(model.skins.size(), 1u);
  EXPECT_EQ(model.skins[0].joints.size(), 19u);
  size_t skinned = 0, channels = 0;
  for (const eng::Node& node : model.nodes) skinned += node.skin == 0 && node.mesh >= 0;
  for (const eng::Animation& anim : model.animations) channels += anim.nodeChannels.size();
  EXPECT_EQ(skinned, 1u);
  EXPECT_EQ(channels, 57u) << "translation, rotation and scale of 19 joints";
  // Bind pose: a T-pose about 1.5 m tall, arms out along Z (he faces +X);
  // walking, the arms come down.
  const eng::Pose rest = eng::restPose(model);
  const eng::Aabb bind = eng::posedBounds(model, rest);
  EXPECT_NEAR(bind.size().y, 1.5f, 0.1f);
  EXPECT_GT(bind.size().z, 1.0f);
  eng::Pose walk = rest;
  for (const eng::Animation& anim : model.animations) eng::sampleAnimation(anim, 0.5f, walk);
  EXPECT_LT(eng::posedBounds(model, walk).size().z, 0.75f * bind.size().z);
  // No joint names: the head is the highest joint that moves vertices, and its region is the top of the body.
  const int head = eng::findHeadJoint(model);
  ASSERT_GE(head, 0);
  EXPECT_TRUE(isSkinJoint(model, head));
  const eng::Aabb face = eng::posedJointRegionBounds(model, rest, head);
  ASSERT_TRUE(face.valid());
  EXPECT_NEAR(face.max.y, bind.max.y, 0.02f);
  EXPECT_GT(face.min.y, bind.min.y + 0.75f * bind.size().y);
  EXPECT_LT(face.size().z, 0.3f * bind.size().z);
}

TEST(SkinningSharedAssets, RobotHandsSitOnItsArmsAndItsHeadJointIsNamed) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model model = loadShared("RobotExpressive.glb");
  ASSERT_EQ(model.skins.size(), 2u);
  const int head = eng::findHeadJoint(model);
  ASSERT_GE(head, 0);
  EXPECT_EQ(model.nodes[head].name, "Head");
  EXPECT_TRUE(isSkinJoint(model, head));
  // Raw vertices put the hands far out to the sides (they float away from
  // the arms); skinned, the robot is narrower than tall.
  const eng::Aabb raw = model.bounds();
  const eng::Aabb posed = eng::posedBounds(model, eng::restPose(model));
  EXPECT_LT(posed.size().x, 0.8f * raw.size().x);
  EXPECT_LT(posed.size().x, posed.size().y);
  const eng::Aabb face = eng::posedJointRegionBounds(model, eng::restPose(model), head);
  ASSERT_TRUE(face.valid());
  EXPECT_GT(face.min.y, posed.center().y) << "the head is the upper part";
  EXPECT_NEAR(face.max.y, posed.max.y, 0.05f * posed.size().y);
}

// Exports from converters and scanners often lose their joint names. Ready
// Player Me's eye joints sit above its head joint: the highest joint that
// moves vertices frames one eyeball, and no face is found in that view.
TEST(SkinningSharedAssets, HeadJointWithoutNamesIsTheHeadNotAnEye) {
  FACIAL_REQUIRE_SHARED();
  auto named = eng::loadModel(testing_support::sharedDir() / "speech" / "rpm-visemes.glb");
  ASSERT_TRUE(named.ok()) << named.error().message;
  const int head = eng::findHeadJoint(*named);
  ASSERT_GE(head, 0);
  ASSERT_EQ(named->nodes[head].name, "Head");
  eng::Model model = *named;
  for (eng::Node& node : model.nodes) node.name = "node";
  EXPECT_EQ(eng::findHeadJoint(model), head) << "found " << named->nodes[eng::findHeadJoint(model)].name;
  const eng::Aabb region = eng::posedJointRegionBounds(model, eng::restPose(model), eng::findHeadJoint(model));
  EXPECT_GT(region.size().y, 0.2f) << "a head, not an eyeball";
}


}  // namespace

namespace {

TEST(SkinningRoundTrip, SavedSkinLoadsBackTheSame) {
  const eng::Model model = loadStrip({.jointType = kUnsignedByte, .weightType = kUnsignedShort,
                                      .secondInfluenceSet = true, .interpolation = "CUBICSPLINE"},
                                     "round_trip_source");
  const auto dir = freshTempDir("skinning_round_trip");
  ASSERT_TRUE(eng::saveModel(model, dir / "saved.glb"));
  auto again = eng::loadModel(dir / "saved.glb");
  ASSERT_TRUE(again) << again.error().message;
  ASSERT_EQ(again->skins.size(), 1u);
  EXPECT_EQ(again->skins[0].joints, model.skins[0].joints);
  EXPECT_EQ(again->skins[0].inverseBindMatrices, model.skins[0].inverseBindMatrices);
  EXPECT_EQ(again->skins[0].skeleton, 1);
  EXPECT_EQ(again->nodes[0].skin, 0);
  const eng::Primitive& a = model.meshes[0].primitives[0];
  const eng::Primitive& b = again->meshes[0].primitives[0];
  EXPECT_EQ(b.joints, a.joints);
  ASSERT_EQ(b.jointWeights.size(), a.jointWeights.size());
  for (size_t i = 0; i < a.jointWeights.size(); ++i)
    EXPECT_LE(glm::length(b.jointWeights[i] - a.jointWeights[i]), 1e-6f) << i;
  ASSERT_EQ(again->animations.size(), 1u);
  ASSERT_EQ(again->animations[0].nodeChannels.size(), 1u);
  EXPECT_EQ(again->animations[0].nodeChannels[0].interpolation, eng::Interpolation::CubicSpline);
  EXPECT_EQ(again->animations[0].nodeChannels[0].values, model.animations[0].nodeChannels[0].values);
}

}  // namespace
