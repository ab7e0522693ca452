#include "facial/runtime/graph/nodes/bilinear_node.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

using Pose = std::vector<float>;

// Two face shapes x three expressions over three channels.
const Pose Q11 = {1.0f, 0.0f, 0.0f}, Q12 = {0.0f, 1.0f, 0.0f}, Q1x = {0.0f, 0.0f, 1.0f};
const Pose Q21 = {0.5f, 0.5f, 0.0f}, Q22 = {0.0f, 0.5f, 0.5f}, Q2x = {0.2f, 0.2f, 0.2f};

Pose mix(float wa, const Pose& a, float wb, const Pose& b) {
  Pose out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = wa * a[i] + wb * b[i];
  return out;
}

// The study's formula Pf = s1 (t1 Qa + t2 Qb) + s2 (t1 Qc + t2 Qd).
Pose study(float s2, float t2, const Pose& qa, const Pose& qb, const Pose& qc, const Pose& qd) {
  return mix(1 - s2, mix(1 - t2, qa, t2, qb), s2, mix(1 - t2, qc, t2, qd));
}

float cosine(float t) { return (1.0f - std::cos(std::numbers::pi_v<float> * t)) / 2.0f; }

struct BilinearRig {
  BilinearRig() {
    GraphBuilder b(threeChannels());
    shape = b.addFloat("shape", 0.25f);
    expression = b.addFloat("expression", 0.0f);
    BilinearNode node;
    for (const Pose* p : {&Q11, &Q12, &Q1x}) node.shape1.push_back(addPose(b, *p));
    for (const Pose* p : {&Q21, &Q22, &Q2x}) node.shape2.push_back(addPose(b, *p));
    node.shape = FloatInput::bound(shape);
    node.expression = expression;
    node.duration = 1.0f;
    node.curve = EasingCurve::cosine();
    b.setRoot(b.add(std::move(node)));
    face.emplace(instantiate(buildGraph(b)));
  }
  Pose step(float dt) {
    face->update(dt);
    return {face->weights().begin(), face->weights().end()};
  }
  ParameterIndex shape = 0, expression = 0;
  std::optional<GraphInstance> face;
};

void expectPose(const Pose& actual, const Pose& expected, float tolerance = 1e-5f) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "channel " << i;
}

}  // namespace

TEST(BilinearNode, BlendsFourKeyframesAsTheStudyFormula) {
  BilinearRig rig;
  expectPose(rig.step(0.0f), study(0.25f, 0.0f, Q11, Q12, Q21, Q22));  // expression 1 on screen
  rig.face->setFloat(rig.expression, 1.0f);
  expectPose(rig.step(0.3f), study(0.25f, cosine(0.3f), Q11, Q12, Q21, Q22));
  expectPose(rig.step(0.3f), study(0.25f, cosine(0.6f), Q11, Q12, Q21, Q22));
  rig.face->setFloat(rig.shape, 0.9f);  // the shape axis follows its parameter directly
  expectPose(rig.step(0.1f), study(0.9f, cosine(0.7f), Q11, Q12, Q21, Q22));
  expectPose(rig.step(5.0f), study(0.9f, 1.0f, Q11, Q12, Q21, Q22));
}

TEST(BilinearNode, NewExpressionMidWayRebasesOnThePairOnScreen) {
  BilinearRig rig;
  rig.step(0.0f);
  rig.face->setFloat(rig.expression, 1.0f);
  const Pose before = rig.step(0.4f);
  const float t2 = cosine(0.4f);
  // Q13 = t1 Q11 + t2 Q12, Q23 = t1 Q21 + t2 Q22.
  const Pose q13 = mix(1 - t2, Q11, t2, Q12), q23 = mix(1 - t2, Q21, t2, Q22);
  rig.face->setFloat(rig.expression, 2.0f);
  expectPose(rig.step(0.0f), before);  // no jump at the re-base
  expectPose(rig.step(0.5f), study(0.25f, cosine(0.5f), q13, Q1x, q23, Q2x));
  expectPose(rig.step(0.5f), study(0.25f, 1.0f, q13, Q1x, q23, Q2x));
}

TEST(BilinearNode, RandomReselectionsNeverMoveFasterThanTheCurveAllows) {
  // Weights lie in [0,1], so source and target differ by at most 1 per
  // channel: one frame moves a weight by at most maxSlope * dt / duration.
  BilinearRig rig;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> dt(0.001f, 0.05f);
  std::uniform_int_distribution<int> column(0, 2);
  Pose previous = rig.step(0.0f);
  for (int frame = 0; frame < 5000; ++frame) {
    if (frame % 13 == 0) rig.face->setFloat(rig.expression, static_cast<float>(column(rng)));
    const float step = dt(rng);
    const Pose now = rig.step(step);
    const float bound = static_cast<float>(EasingCurve::cosine().maxSlope()) * step / 1.0f + 1e-5f;
    for (size_t c = 0; c < now.size(); ++c) ASSERT_LE(std::abs(now[c] - previous[c]), bound) << "frame " << frame;
    previous = now;
  }
}

TEST(BilinearNodeValidity, NeedsTwoEqualRowsAPositiveDurationAndAFloatExpression) {
  GraphBuilder b(threeChannels());
  const ParameterIndex e = b.addFloat("e");
  const ParameterIndex trig = b.addTrigger("go");
  BilinearNode node{.shape1 = {addPose(b, Q11), addPose(b, Q12)}, .shape2 = {addPose(b, Q21)}, .expression = e};
  const NodeIndex root = b.add(node);
  b.setRoot(root);
  EXPECT_NE(buildError(b).find("/shapes: needs two rows"), std::string::npos);

  GraphBuilder c(threeChannels());
  c.addFloat("e");
  const ParameterIndex go = c.addTrigger("go");
  BilinearNode bad{.shape1 = {addPose(c, Q11), addPose(c, Q12)}, .shape2 = {addPose(c, Q21), addPose(c, Q22)},
                   .expression = go, .duration = 0.5f};
  c.setRoot(c.add(bad));
  EXPECT_NE(buildError(c).find("/expression: parameter 'go' is a trigger, expected a float"), std::string::npos);
  (void)trig;

  GraphBuilder d(threeChannels());
  const ParameterIndex de = d.addFloat("e");
  BilinearNode zero{.shape1 = {addPose(d, Q11), addPose(d, Q12)}, .shape2 = {addPose(d, Q21), addPose(d, Q22)},
                    .expression = de, .duration = 0.0f};
  d.setRoot(d.add(zero));
  EXPECT_NE(buildError(d).find("/duration: must be a finite number > 0"), std::string::npos);
}
