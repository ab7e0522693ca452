// editor/bilinear_pad.h: the study's bilinear blend of four poses and its
// re-basing when a new expression is chosen mid-way (the face does not jump).
#include <cmath>

#include <gtest/gtest.h>

#include "editor/bilinear_pad.h"

namespace {

using editor::BilinearPad;

BilinearPad pad() {
  BilinearPad p;
  EXPECT_TRUE(p.setCorners({std::vector<float>{0, 0}, {1, 0}, {0, 1}, {1, 1}}).ok());
  return p;
}

std::vector<float> poseOf(const BilinearPad& p) {
  std::vector<float> out(p.poseSize());
  EXPECT_TRUE(p.pose(out).ok());
  return out;
}

}  // namespace

TEST(BilinearPad, BlendsTheFourCornersBilinearly) {
  BilinearPad p = pad();
  p.setPosition(0.25f, 0.5f);
  EXPECT_EQ(poseOf(p), (std::vector<float>{0.5f, 0.25f}));
  p.setPosition(2.0f, NAN);  // clamped, the NaN ignored
  EXPECT_EQ(p.s(), 1.0f);
  EXPECT_EQ(p.t(), 0.5f);
}

TEST(BilinearPad, ANewExpressionMidWayReBasesWithoutAJump) {
  BilinearPad p = pad();
  p.setPosition(0.5f, 0.6f);
  const std::vector<float> before = poseOf(p);
  const std::vector<float> next = {0.0f, 0.0f};
  ASSERT_TRUE(p.chooseCorner(BilinearPad::Q12, next).ok());
  EXPECT_EQ(p.t(), 0.0f);
  const std::vector<float> after = poseOf(p);
  EXPECT_NEAR(after[0], before[0], 1e-6f);
  EXPECT_NEAR(after[1], before[1], 1e-6f);
  p.setPosition(0.5f, 1.0f);
  EXPECT_NEAR(poseOf(p)[0], 0.5f * 0.0f + 0.5f * 1.0f, 1e-6f) << "row 1 reached the new expression, row 2 its old one";
}

TEST(BilinearPad, AFromCornerIsReplacedAsItIs) {
  BilinearPad p = pad();
  p.setPosition(0.0f, 0.0f);
  const std::vector<float> smile = {0.3f, 0.3f};
  ASSERT_TRUE(p.chooseCorner(BilinearPad::Q11, smile).ok());
  EXPECT_EQ(poseOf(p), smile);
  EXPECT_EQ(p.chooseCorner(BilinearPad::Q22, std::vector<float>{1.0f}).error().message,
            "bilinear pad: a pose of 1 weights, the pad's poses have 2");
}
