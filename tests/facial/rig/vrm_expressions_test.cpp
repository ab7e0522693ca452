// VrmExpressionSet::apply: binds accumulate; isBinary; the VRM 1.0 override
// rules for the blink / lookAt / mouth groups.
#include "facial/runtime/rig/vrm_expressions.h"

#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace facial {
namespace {

// Targets: 0 smile, 1 eyes closed, 2 frown, 3 mouth open, 4 look up.
// Expressions: 0 happy, 1 blink, 2 angry, 3 aa, 4 lookUp, 5 sad.
VrmExpressionSet makeSet() {
  VrmExpressionSet set;
  set.targetNames = {"Face/smile", "Face/eyesClosed", "Face/frown", "Face/mouthOpen", "Face/lookUp"};
  set.meshTargetOffsets = {0, 5};
  auto add = [&](std::string name, VrmProceduralGroup group, std::vector<VrmMorphBind> binds) {
    VrmExpression e;
    e.name = std::move(name);
    e.isPreset = true;
    e.group = group;
    e.firstBind = static_cast<uint32_t>(set.binds.size());
    e.bindCount = static_cast<uint32_t>(binds.size());
    set.binds.insert(set.binds.end(), binds.begin(), binds.end());
    set.expressions.push_back(e);
    return set.expressions.size() - 1;
  };
  add("happy", VrmProceduralGroup::None, {{0, 1.0f}, {1, 0.3f}});
  add("blink", VrmProceduralGroup::Blink, {{1, 1.0f}});
  add("angry", VrmProceduralGroup::None, {{2, 0.8f}});
  add("aa", VrmProceduralGroup::Mouth, {{3, 1.0f}});
  add("lookUp", VrmProceduralGroup::LookAt, {{4, 1.0f}});
  add("sad", VrmProceduralGroup::None, {{2, 0.5f}});
  return set;
}

std::vector<float> run(const VrmExpressionSet& set, std::vector<float> weights) {
  std::vector<float> targets(set.targetCount(), -1.0f);
  auto result = set.apply(weights, targets);
  EXPECT_TRUE(result) << result.error().message;
  return targets;
}

TEST(VrmExpressions, BindsAccumulateScaledByWeight) {
  const VrmExpressionSet set = makeSet();
  ASSERT_TRUE(set.validate());
  const std::vector<float> t = run(set, {0.5f, 0, 0.5f, 0, 0, 1.0f});
  EXPECT_FLOAT_EQ(t[0], 0.5f);
  EXPECT_FLOAT_EQ(t[1], 0.15f);
  EXPECT_FLOAT_EQ(t[2], 0.4f + 0.5f);  // angry and sad both bind the frown
  EXPECT_FLOAT_EQ(t[3], 0.0f);          // every target written, unbound ones 0
  // Inputs clamp to [0,1].
  EXPECT_FLOAT_EQ(run(set, {3.0f, 0, 0, 0, 0, 0})[0], 1.0f);
  EXPECT_FLOAT_EQ(run(set, {-1.0f, 0, 0, 0, 0, 0})[0], 0.0f);
}

// An expression moves the face when a bind of it has weight, or it binds a
// material: a file exported from a model without blend shapes keeps the
// presets with nothing bound.
TEST(VrmExpressions, AnExpressionMovesWhenItBindsSomething) {
  VrmExpressionSet set = makeSet();
  EXPECT_TRUE(set.moves(0));
  set.binds[set.expressions[2].firstBind].weight = 0.0f;  // angry's one bind at 0
  EXPECT_FALSE(set.moves(2));
  set.expressions[2].materialColorBindCount = 1;
  set.materialColorBinds.push_back({});
  EXPECT_TRUE(set.moves(2));
  VrmExpression empty;
  empty.name = "relaxed";
  empty.firstBind = static_cast<uint32_t>(set.binds.size());
  set.expressions.push_back(empty);
  EXPECT_FALSE(set.moves(set.expressions.size() - 1));
  EXPECT_FALSE(set.moves(set.expressions.size())) << "past the end";
}

TEST(VrmExpressions, BlockZeroesTheGroupWhileTheOverriderIsActive) {
  VrmExpressionSet set = makeSet();
  set.expressions[0].overrideBlink = VrmOverride::Block;
  EXPECT_FLOAT_EQ(run(set, {0, 1.0f, 0, 0, 0, 0})[1], 1.0f);      // blink alone
  EXPECT_FLOAT_EQ(run(set, {0.01f, 1.0f, 0, 0, 0, 0})[1], 0.003f);  // blocked: only happy's own 0.3 bind remains
  EXPECT_FLOAT_EQ(run(set, {0.01f, 0, 0, 1.0f, 0, 0})[3], 1.0f);   // other groups unaffected
}

TEST(VrmExpressions, BlendAttenuatesBySaturatedSumOfOverriders) {
  VrmExpressionSet set = makeSet();
  set.expressions[2].overrideMouth = VrmOverride::Blend;  // angry
  set.expressions[5].overrideMouth = VrmOverride::Blend;  // sad
  EXPECT_FLOAT_EQ(run(set, {0, 0, 0.25f, 1.0f, 0, 0})[3], 0.75f);
  EXPECT_FLOAT_EQ(run(set, {0, 0, 0.25f, 1.0f, 0, 0.5f})[3], 0.25f);
  EXPECT_FLOAT_EQ(run(set, {0, 0, 0.75f, 1.0f, 0, 0.75f})[3], 0.0f);  // sum 1.5 saturates
  // Block wins over blend.
  set.expressions[0].overrideMouth = VrmOverride::Block;
  EXPECT_FLOAT_EQ(run(set, {0.1f, 0, 0.25f, 1.0f, 0, 0})[3], 0.0f);
}

TEST(VrmExpressions, OverrideOnItsOwnGroupIsIgnored) {
  VrmExpressionSet set = makeSet();
  set.expressions[1].overrideBlink = VrmOverride::Block;  // blink overriding blink: invalid per spec
  set.expressions[3].overrideLookAt = VrmOverride::Block;  // aa may override another group
  const std::vector<float> t = run(set, {0, 1.0f, 0, 1.0f, 1.0f, 0});
  EXPECT_FLOAT_EQ(t[1], 1.0f);
  EXPECT_FLOAT_EQ(t[4], 0.0f);
}

TEST(VrmExpressions, BinaryExpressionsSnapAndOverrideWithTheirSnappedWeight) {
  VrmExpressionSet set = makeSet();
  set.expressions[0].isBinary = true;
  set.expressions[0].overrideBlink = VrmOverride::Blend;
  EXPECT_FLOAT_EQ(run(set, {0.4f, 0, 0, 0, 0, 0})[0], 0.0f);
  EXPECT_FLOAT_EQ(run(set, {0.6f, 0, 0, 0, 0, 0})[0], 1.0f);
  // happy at 0.4 is 0 after snapping: it does not attenuate blink at all.
  EXPECT_FLOAT_EQ(run(set, {0.4f, 1.0f, 0, 0, 0, 0})[1], 1.0f);
  // happy at 0.6 snaps to 1: blend factor 0, blink gone (only happy's own bind).
  EXPECT_FLOAT_EQ(run(set, {0.6f, 1.0f, 0, 0, 0, 0})[1], 0.3f);
}

TEST(VrmExpressions, BinaryOverriddenExpressionIsSuppressedByAnyEffect) {
  VrmExpressionSet set = makeSet();
  set.expressions[1].isBinary = true;                    // blink
  set.expressions[2].overrideBlink = VrmOverride::Blend;  // angry
  EXPECT_FLOAT_EQ(run(set, {0, 1.0f, 0, 0, 0, 0})[1], 1.0f);
  EXPECT_FLOAT_EQ(run(set, {0, 1.0f, 0.05f, 0, 0, 0})[1], 0.0f);  // blend factor 0.95 -> suppressed, not 0.95
}

TEST(VrmExpressions, GroupsFromPresetNames) {
  EXPECT_EQ(vrmProceduralGroup("blinkLeft"), VrmProceduralGroup::Blink);
  EXPECT_EQ(vrmProceduralGroup("blink_r"), VrmProceduralGroup::Blink);
  EXPECT_EQ(vrmProceduralGroup("lookDown"), VrmProceduralGroup::LookAt);
  EXPECT_EQ(vrmProceduralGroup("ou"), VrmProceduralGroup::Mouth);
  EXPECT_EQ(vrmProceduralGroup("a"), VrmProceduralGroup::Mouth);  // VRM 0.x
  EXPECT_EQ(vrmProceduralGroup("happy"), VrmProceduralGroup::None);
}

// ---- refused calls and inconsistent sets ----

TEST(VrmExpressionsValidity, ApplyNamesSizesAndNonFiniteWeights) {
  const VrmExpressionSet set = makeSet();
  std::vector<float> targets(5, 7.0f);
  const std::vector<float> tooFew(3, 0.0f);
  auto wrong = set.apply(tooFew, targets);
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("3 expression weights and 5 target weights; expected 6 and 5"),
            std::string::npos)
      << wrong.error().message;
  EXPECT_EQ(targets[0], 7.0f);  // nothing written
  std::vector<float> nan(6, 0.0f);
  nan[2] = std::numeric_limits<float>::quiet_NaN();
  auto bad = set.apply(nan, targets);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("'angry' is not finite"), std::string::npos) << bad.error().message;
}

TEST(VrmExpressionsValidity, ValidateCatchesBrokenIndices) {
  VrmExpressionSet set = makeSet();
  set.binds[0].target = 9;
  EXPECT_FALSE(set.validate());
  set = makeSet();
  set.expressions[5].bindCount = 4;
  auto r = set.validate();
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("'sad' binds"), std::string::npos) << r.error().message;
  set = makeSet();
  set.meshTargetOffsets = {0, 4};
  EXPECT_FALSE(set.validate());
}

}  // namespace
}  // namespace facial
