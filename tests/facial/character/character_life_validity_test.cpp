// Bad input to CharacterLife: refused with a message, nothing changes.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "facial/runtime/character/character_life.h"

using namespace facial;

TEST(CharacterLifeValidity, RefusesLimitsOutsideZeroToNinety) {
  for (float bad : {-1.0f, 91.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    CharacterLifeOptions options;
    options.right.up = bad;
    auto life = CharacterLife::create(options);
    ASSERT_FALSE(life) << bad;
    EXPECT_NE(life.error().message.find("eye limits"), std::string::npos);
  }
}

TEST(CharacterLifeValidity, RefusesNonFiniteEyeCentres) {
  CharacterLifeOptions options;
  options.leftEye.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(CharacterLife::create(options));
}

TEST(CharacterLifeValidity, NonFiniteLookAtTargetKeepsThePreviousOne) {
  auto life = CharacterLife::create({.sway = false, .saccades = false});
  ASSERT_TRUE(life);
  ASSERT_TRUE(life->lookAt({0.1f, 0.0f, 1.0f}));
  auto refused = life->lookAt({std::numeric_limits<float>::infinity(), 0.0f, 1.0f});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("not finite"), std::string::npos);
  ASSERT_TRUE(life->lookAtTarget());
  EXPECT_EQ(life->lookAtTarget()->x, 0.1f);
}

TEST(CharacterLifeValidity, NegativeOrNonFiniteTimeStepChangesNothing) {
  auto life = CharacterLife::create({.seed = 2});
  ASSERT_TRUE(life);
  life->update(0.5f);
  const glm::quat before = life->headRotation();
  EXPECT_FALSE(life->update(-0.1f));
  EXPECT_FALSE(life->update(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_EQ(life->headRotation(), before);
}
