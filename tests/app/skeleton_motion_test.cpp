// app/skeleton_motion.h: skeletal clips chosen by name, index or "all", the
// idle head turn going to the head joint of skinned avatars (only), and the
// gaze to eye joints, or to the eye nodes of an unskinned face whose morph
// targets do not steer its eyes.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "app/skeleton_motion.h"
#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace {

eng::Model loadShared(const std::string& relative) {
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / relative);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  return model.ok() ? std::move(*model) : eng::Model{};
}

glm::vec3 position(const glm::mat4& m) { return glm::vec3(m[3]); }

TEST(SkeletonMotion, PicksClipsByNameIndexOrAll) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model robot = loadShared("RobotExpressive.glb");
  auto wave = app::SkeletonMotion::create(robot, "Wave");
  ASSERT_TRUE(wave) << wave.error().message;
  EXPECT_EQ(wave->clipLabel(), "Wave");
  EXPECT_TRUE(wave->active());
  auto byIndex = app::SkeletonMotion::create(robot, "12");
  ASSERT_TRUE(byIndex) << byIndex.error().message;
  EXPECT_EQ(byIndex->clipLabel(), "Wave");
  const eng::Model cesium = loadShared("khronos/CesiumMan/glTF-Binary/CesiumMan.glb");
  auto all = app::SkeletonMotion::create(cesium, "all");
  ASSERT_TRUE(all) << all.error().message;
  EXPECT_EQ(all->clipLabel(), "all 19 clips");
  // The pose moves with time and the clip loops.
  all->update(0.3f);
  const std::vector<glm::mat4> early(all->nodeWorld().begin(), all->nodeWorld().end());
  all->update(0.3f + all->clipDuration());
  for (size_t n = 0; n < early.size(); ++n)
    EXPECT_LE(glm::length(position(all->nodeWorld()[n]) - position(early[n])), 1e-4f) << n;
  all->update(0.6f);
  float moved = 0.0f;
  for (size_t n = 0; n < early.size(); ++n) moved = std::max(moved, glm::length(position(all->nodeWorld()[n]) - position(early[n])));
  EXPECT_GT(moved, 0.01f);
}

TEST(SkeletonMotion, UnknownClipIsOneErrorListingTheClips) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model robot = loadShared("RobotExpressive.glb");
  for (const char* clip : {"Moonwalk", "14"}) {
    auto motion = app::SkeletonMotion::create(robot, clip);
    ASSERT_FALSE(motion) << clip;
    EXPECT_NE(motion.error().message.find("RobotExpressive.glb: no skeletal clip '" + std::string(clip) + "'"),
              std::string::npos) << motion.error().message;
    EXPECT_NE(motion.error().message.find("12 'Wave' (1.8 s)"), std::string::npos) << motion.error().message;
  }
  const eng::Model simple = loadShared("khronos/SimpleMorph/SimpleMorph.gltf");  // a weights animation only
  auto none = app::SkeletonMotion::create(simple, "all");
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("has no skeletal clip"), std::string::npos) << none.error().message;
}

TEST(SkeletonMotion, HeadTurnTurnsOnlyTheHeadJointAboutItself) {
  FACIAL_REQUIRE_SHARED();
  const eng::Model robot = loadShared("RobotExpressive.glb");
  auto motion = app::SkeletonMotion::create(robot, "");
  ASSERT_TRUE(motion) << motion.error().message;
  ASSERT_TRUE(motion->turnsHeadJoint());
  const int head = motion->headJoint();
  const int neck = robot.nodes[head].parent;
  ASSERT_GE(neck, 0);
  motion->update(0.0f);
  const std::vector<glm::mat4> still(motion->nodeWorld().begin(), motion->nodeWorld().end());
  const glm::quat turn = glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0));
  motion->update(0.0f, turn);
  const auto turned = motion->nodeWorld();
  EXPECT_LE(glm::length(position(turned[head]) - position(still[head])), 1e-5f) << "turns about the joint";
  EXPECT_EQ(turned[neck], still[neck]) << "the body stays";
  // The head's world rotation gained exactly the turn, in model-space axes.
  const glm::mat3 expected = glm::mat3_cast(turn) * glm::mat3(still[head]);
  for (int c = 0; c < 3; ++c) EXPECT_LE(glm::length(glm::mat3(turned[head])[c] - expected[c]), 1e-4f) << c;
}

// A skinned head with two eye joints (VRoid's names, under a "prefix:" as exporters write them).
eng::Model headWithEyes() {
  eng::Model model;
  const char* names[] = {"Hips", "Head", "rig:J_Adj_L_FaceEye", "rig:J_Adj_R_FaceEye"};
  const glm::vec3 at[] = {{0, 1, 0}, {0, 0.6f, 0}, {0.03f, 0.08f, 0.08f}, {-0.03f, 0.08f, 0.08f}};
  const int parents[] = {-1, 0, 1, 1};
  for (int n = 0; n < 4; ++n) {
    eng::Node node;
    node.name = names[n];
    node.translation = at[n];
    node.parent = parents[n];
    if (parents[n] >= 0) model.nodes[size_t(parents[n])].children.push_back(n);
    model.nodes.push_back(node);
  }
  model.roots = {0};
  model.skins.push_back(eng::Skin{.name = "body", .joints = {0, 1, 2, 3}, .inverseBindMatrices = std::vector<glm::mat4>(4, glm::mat4(1.0f))});
  return model;
}

TEST(SkeletonMotion, EyeJointsTakeTheGazeAboutThemselves) {
  const eng::Model model = headWithEyes();
  auto motion = app::SkeletonMotion::create(model, "");
  ASSERT_TRUE(motion) << motion.error().message;
  EXPECT_EQ(motion->headJoint(), 1);
  EXPECT_EQ(motion->eyeJoints()[0], 2);
  EXPECT_EQ(motion->eyeJoints()[1], 3);
  motion->update(0.0f);
  const std::vector<glm::mat4> still(motion->nodeWorld().begin(), motion->nodeWorld().end());
  const glm::quat left = glm::angleAxis(glm::radians(20.0f), glm::vec3(0, 1, 0));
  const glm::quat right = glm::angleAxis(glm::radians(-10.0f), glm::vec3(1, 0, 0));
  motion->update(0.0f, glm::quat(1, 0, 0, 0), {left, right});
  const auto turned = motion->nodeWorld();
  EXPECT_EQ(turned[1], still[1]) << "the head stays";
  for (int eye : {2, 3}) {
    EXPECT_LE(glm::length(position(turned[size_t(eye)]) - position(still[size_t(eye)])), 1e-6f) << "turns in place";
    const glm::vec3 gaze = glm::mat3(turned[size_t(eye)]) * glm::vec3(0, 0, 1);
    const glm::vec3 want = (eye == 2 ? left : right) * glm::vec3(0, 0, 1);
    EXPECT_LE(glm::length(gaze - want), 1e-5f) << eye;
  }
}

TEST(SkeletonMotion, BuiltInHeadTurnsItsEyeballsInTheirSockets) {
  auto loaded = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(loaded) << loaded.error().message;
  const eng::Model& head = *loaded;
  auto motion = app::SkeletonMotion::create(head, "");
  ASSERT_TRUE(motion) << motion.error().message;
  EXPECT_FALSE(motion->turnsHeadJoint()) << "no skin: the demo turns the whole head";
  ASSERT_TRUE(motion->active());
  const std::array<int, 2> eyes = motion->eyeJoints();
  ASSERT_GE(eyes[0], 0);
  ASSERT_GE(eyes[1], 0);
  EXPECT_EQ(head.nodes[size_t(eyes[0])].name, "EyeLeft");
  EXPECT_EQ(head.nodes[size_t(eyes[1])].name, "EyeRight");
  motion->update(0.0f);
  const std::vector<glm::mat4> still(motion->nodeWorld().begin(), motion->nodeWorld().end());
  const glm::quat lookLeft = glm::angleAxis(glm::radians(12.0f), glm::vec3(0, 1, 0));
  motion->update(0.0f, glm::quat(1, 0, 0, 0), {lookLeft, lookLeft});
  const auto turned = motion->nodeWorld();
  for (int eye : eyes) {
    EXPECT_LE(glm::length(position(turned[size_t(eye)]) - position(still[size_t(eye)])), 1e-6f) << "turns in place";
    EXPECT_LE(glm::length(glm::mat3(turned[size_t(eye)]) * glm::vec3(0, 0, 1) - lookLeft * glm::vec3(0, 0, 1)), 1e-5f);
  }
  for (size_t n = 0; n < head.nodes.size(); ++n) {
    if (int(n) == eyes[0] || int(n) == eyes[1]) continue;
    EXPECT_EQ(turned[n], still[n]) << head.nodes[n].name;
  }
}

TEST(SkeletonMotion, UnskinnedFaceWhoseMorphsSteerTheEyesHasNothingToPose) {
  // facecap has eye nodes too, but its eyeLook shapes already turn the balls:
  // turning the nodes as well would double the gaze.
  FACIAL_REQUIRE_SHARED();
  const eng::Model facecap = loadShared("facecap.glb");
  auto motion = app::SkeletonMotion::create(facecap, "");
  ASSERT_TRUE(motion) << motion.error().message;
  EXPECT_FALSE(motion->turnsHeadJoint());
  EXPECT_FALSE(motion->active());
  motion->update(1.0f, glm::angleAxis(0.3f, glm::vec3(0, 1, 0)));
  EXPECT_TRUE(motion->nodeWorld().empty());
}

}  // namespace
