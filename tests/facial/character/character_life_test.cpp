#include "facial/runtime/character/character_life.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

using namespace facial;

namespace {

CharacterLife still(CharacterLifeOptions options = {}) {
  options.sway = false;
  options.saccades = false;
  auto life = CharacterLife::create(options);
  EXPECT_TRUE(life) << life.error().message;
  return std::move(*life);
}

glm::vec3 direction(const glm::quat& rotation) { return rotation * glm::vec3(0.0f, 0.0f, 1.0f); }

}  // namespace

TEST(CharacterLife, LooksStraightAheadWithoutTarget) {
  CharacterLife life = still();
  life.update(1.0f);
  for (Eye eye : {Eye::Left, Eye::Right}) {
    EXPECT_EQ(life.eyeGaze(eye).yaw, 0.0f);
    EXPECT_EQ(life.eyeGaze(eye).pitch, 0.0f);
  }
  EXPECT_EQ(life.headRotation(), glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  EXPECT_EQ(life.breathLift(), 0.0f);
}

TEST(CharacterLife, EyeRotationPointsAtTheTarget) {
  CharacterLifeOptions options;
  options.leftEye = {0.03f, 0.0f, 0.0f};
  options.rightEye = {-0.03f, 0.0f, 0.0f};
  CharacterLife life = still(options);
  const glm::vec3 target(0.2f, 0.1f, 1.0f);  // within every limit
  ASSERT_TRUE(life.lookAt(target));
  for (Eye eye : {Eye::Left, Eye::Right}) {
    const glm::vec3 from = eye == Eye::Left ? options.leftEye : options.rightEye;
    const glm::vec3 want = glm::normalize(target - from);
    const glm::vec3 got = direction(life.eyeRotation(eye));
    EXPECT_NEAR(got.x, want.x, 1e-5f);
    EXPECT_NEAR(got.y, want.y, 1e-5f);
    EXPECT_NEAR(got.z, want.z, 1e-5f);
  }
}

TEST(CharacterLife, NearTargetsMakeTheEyesConverge) {
  CharacterLife life = still();
  ASSERT_TRUE(life.lookAt({0.0f, 0.0f, 0.15f}));  // a finger in front of the nose
  EXPECT_LT(life.eyeGaze(Eye::Left).yaw, -0.1f);  // the left eye turns toward -X (inward)
  EXPECT_GT(life.eyeGaze(Eye::Right).yaw, 0.1f);
  EXPECT_NEAR(life.eyeGaze(Eye::Left).yaw, -life.eyeGaze(Eye::Right).yaw, 1e-6f);
}

TEST(CharacterLife, EachEyeStopsAtItsOwnLimits) {
  CharacterLifeOptions options;
  options.left = {.inward = 10.0f, .outward = 40.0f, .up = 5.0f, .down = 20.0f};
  options.right = {.inward = 15.0f, .outward = 25.0f, .up = 5.0f, .down = 20.0f};
  CharacterLife life = still(options);
  ASSERT_TRUE(life.lookAt({100.0f, 100.0f, 1.0f}));  // far to the face's left and up
  // Toward +X the left eye looks outward, the right eye inward.
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Left).yaw), 40.0f, 1e-3f);
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Right).yaw), 15.0f, 1e-3f);
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Left).pitch), 5.0f, 1e-3f);
  ASSERT_TRUE(life.lookAt({-100.0f, -100.0f, 1.0f}));
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Left).yaw), -10.0f, 1e-3f);
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Right).yaw), -25.0f, 1e-3f);
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Right).pitch), -20.0f, 1e-3f);
}

TEST(CharacterLife, TargetBehindTheHeadIsClampedNotFlipped) {
  CharacterLife life = still();
  ASSERT_TRUE(life.lookAt({0.5f, 0.0f, -1.0f}));  // behind, to the left
  EXPECT_NEAR(glm::degrees(life.eyeGaze(Eye::Left).yaw), 35.0f, 1e-3f);  // outward limit, still toward +X
  life.lookAhead();
  EXPECT_EQ(life.eyeGaze(Eye::Left).yaw, 0.0f);
}

TEST(CharacterLife, SaccadesMoveTheEyesAroundTheTargetWithinAFewDegrees) {
  auto life = CharacterLife::create({.seed = 7, .sway = false});
  ASSERT_TRUE(life);
  float largest = 0.0f, moved = 0.0f;
  glm::vec2 previous = life->saccade();
  for (int frame = 0; frame < 600; ++frame) {  // 10 s at 60 Hz
    life->update(1.0f / 60.0f);
    largest = std::max(largest, std::abs(glm::degrees(life->saccade().x)));
    moved += glm::length(life->saccade() - previous);
    previous = life->saccade();
    // Both eyes get the same saccade.
    EXPECT_NEAR(life->eyeGaze(Eye::Left).yaw, life->eyeGaze(Eye::Right).yaw, 1e-6f);
  }
  EXPECT_GT(moved, glm::radians(5.0f));  // several jumps in 10 s
  EXPECT_LE(largest, 10.5f + 1e-3f);
}

TEST(CharacterLife, SameSeedSameLifeOtherSeedOtherLife) {
  auto a = CharacterLife::create({.seed = 3});
  auto b = CharacterLife::create({.seed = 3});
  auto c = CharacterLife::create({.seed = 4});
  ASSERT_TRUE(a && b && c);
  for (int frame = 0; frame < 120; ++frame) {
    a->update(1.0f / 60.0f);
    b->update(1.0f / 60.0f);
    c->update(1.0f / 60.0f);
  }
  EXPECT_EQ(a->headRotation(), b->headRotation());
  EXPECT_EQ(a->saccade(), b->saccade());
  EXPECT_NE(a->headRotation(), c->headRotation());
}

TEST(CharacterLife, SwayIsSmallAndBreathingLiftsALittle) {
  auto life = CharacterLife::create({.seed = 1, .saccades = false});
  ASSERT_TRUE(life);
  float largestTurn = 0.0f, lowest = 1.0f, highest = 0.0f;
  for (int frame = 0; frame < 60 * 20; ++frame) {
    life->update(1.0f / 60.0f);
    largestTurn = std::max(largestTurn, glm::degrees(glm::angle(life->headRotation())));
    lowest = std::min(lowest, life->breathLift());
    highest = std::max(highest, life->breathLift());
  }
  EXPECT_GT(largestTurn, 1.0f);
  EXPECT_LT(largestTurn, 6.0f);
  EXPECT_GE(lowest, 0.0f);
  EXPECT_GT(highest - lowest, 0.003f);
  EXPECT_LT(highest, 0.004f);
}
