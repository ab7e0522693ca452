#include "facial/runtime/graph/nodes/state_machine_node.h"

#include <gtest/gtest.h>

#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

using Pose = std::vector<float>;

TransitionCondition trigger(ParameterIndex p) { return {p, ConditionOp::Triggered, 0.0f}; }

// States A = (0,0,0), B = (1,0,0), C = (0,1,0), D = (0,0,1).
//   A -> B on trigger toB (1 s, linear)       B -> C on trigger toC (0.5 s)
//   A -> C when flag is true (0.5 s)          C -> A after 2 s in C (exit time, 1 s)
//   any -> D when level > 0.5 (1 s, priority 1)
struct Machine {
  explicit Machine(bool interruptible = true) {
    GraphBuilder b(threeChannels());
    toB = b.addTrigger("toB");
    toC = b.addTrigger("toC");
    flag = b.addBool("flag");
    level = b.addFloat("level");
    StateMachineNode m;
    m.states = {{"A", addPose(b, {0, 0, 0}), {}}, {"B", addPose(b, {1, 0, 0}), {}},
                {"C", addPose(b, {0, 1, 0}), {}}, {"D", addPose(b, {0, 0, 1}), {}}};
    m.states[0].transitions.push_back({.to = "B", .duration = 1.0f, .interruptible = interruptible, .conditions = {trigger(toB)}});
    m.states[0].transitions.push_back({.to = "C", .duration = 0.5f, .conditions = {{flag, ConditionOp::IsTrue}}});
    m.states[1].transitions.push_back({.to = "C", .duration = 0.5f, .conditions = {trigger(toC)}});
    m.states[2].transitions.push_back({.to = "A", .duration = 1.0f, .exitTime = 2.0f});
    m.anyState.push_back({.to = "D", .duration = 1.0f, .priority = 1, .conditions = {{level, ConditionOp::Greater, 0.5f}}});
    machine = b.add(std::move(m));
    b.setRoot(machine);
    face.emplace(instantiate(buildGraph(b)));
    face->update(0.0f);  // first frame on screen
  }
  Pose step(float dt) {
    face->update(dt);
    return {face->weights().begin(), face->weights().end()};
  }
  StateMachineStatus status() const { return *face->stateMachineStatus(machine); }
  ParameterIndex toB = 0, toC = 0, flag = 0, level = 0;
  NodeIndex machine = 0;
  std::optional<GraphInstance> face;
};

void expectPose(const Pose& actual, const Pose& expected) {
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(actual[i], expected[i], 1e-5f) << "channel " << i;
}

}  // namespace

TEST(StateMachineNode, TriggerStartsABlendAndIsConsumed) {
  Machine m;
  m.face->setTrigger(m.toB);
  expectPose(m.step(0.25f), {0, 0, 0});  // the transition starts this frame, from what is on screen
  EXPECT_EQ(m.face->parameters()[m.toB], 0.0f);
  EXPECT_TRUE(m.status().blending);
  EXPECT_EQ(m.status().liveSource, 0u);  // uninterrupted: the source state stays live
  expectPose(m.step(0.25f), {0.25f, 0, 0});
  expectPose(m.step(0.5f), {0.75f, 0, 0});
  expectPose(m.step(0.25f), {1, 0, 0});
  EXPECT_FALSE(m.status().blending);
  EXPECT_EQ(m.status().current, 1u);
}

TEST(StateMachineNode, BoolConditionsAndExitTimes) {
  Machine m;
  m.face->setBool(m.flag, true);
  m.step(0.1f);
  m.face->setBool(m.flag, false);
  expectPose(m.step(0.5f), {0, 1, 0});
  EXPECT_EQ(m.status().current, 2u);
  m.step(1.3f);  // 1.8 s in C
  EXPECT_EQ(m.status().current, 2u);
  m.step(0.3f);  // 2.1 s: exit time reached
  EXPECT_EQ(m.status().current, 0u);
  EXPECT_TRUE(m.status().blending);
}

TEST(StateMachineNode, ExitTimeCrossedMidStepStartsTheTransitionAtTheExitTime) {
  Machine m;
  m.face->setBool(m.flag, true);
  m.step(0.1f);
  m.face->setBool(m.flag, false);
  m.step(0.5f);
  m.step(1.4f);  // 1.9 s in C
  EXPECT_EQ(m.status().current, 2u);
  // 2.15 s: the exit (2 s) was 0.15 s ago, so C -> A (1 s, linear) is 0.15 s along, not starting now.
  expectPose(m.step(0.25f), {0, 0.85f, 0});
  EXPECT_EQ(m.status().current, 0u);
  EXPECT_NEAR(m.status().stateTime, 0.15f, 1e-5f);
  // The blend ends 1 s after the exit time, not 1 s after the step that noticed it.
  expectPose(m.step(0.85f), {0, 0, 0});
  EXPECT_FALSE(m.status().blending);
}

TEST(StateMachineNode, HigherPriorityWinsAndAnyStateReachesEveryState) {
  Machine m;
  m.face->setTrigger(m.toB);
  m.face->setFloat(m.level, 0.9f);
  m.step(0.1f);
  EXPECT_EQ(m.status().current, 3u);                  // any -> D (priority 1) beat A -> B
  EXPECT_EQ(m.face->parameters()[m.toB], 1.0f);       // the losing trigger stays set
  ASSERT_TRUE(m.face->resetTrigger(m.toB));
  m.step(2.0f);
  EXPECT_EQ(m.status().current, 3u);                  // no self-transition while level stays high
  EXPECT_FALSE(m.status().blending);
}

TEST(StateMachineNode, InterruptionBlendsFromTheSnapshotOnScreen) {
  Machine m;
  m.face->setTrigger(m.toB);
  m.step(0.0f);
  const Pose midway = m.step(0.5f);
  expectPose(midway, {0.5f, 0, 0});
  m.face->setTrigger(m.toC);  // B -> C cuts into A -> B
  expectPose(m.step(0.0f), midway);  // starts exactly where the face is
  EXPECT_TRUE(m.status().fromSnapshot);
  expectPose(m.step(0.25f), {0.25f, 0.5f, 0});
  expectPose(m.step(0.25f), {0, 1, 0});
}

TEST(StateMachineNode, NonInterruptibleTransitionsFinishFirst) {
  Machine m(/*interruptible=*/false);
  m.face->setTrigger(m.toB);
  m.step(0.0f);
  m.step(0.5f);
  m.face->setTrigger(m.toC);
  m.step(0.25f);
  EXPECT_EQ(m.status().current, 1u);  // still A -> B
  EXPECT_EQ(m.face->parameters()[m.toC], 1.0f);
  m.step(0.3f);  // A -> B completes (1.05 s), then B -> C fires from B, live
  EXPECT_EQ(m.status().current, 2u);
  EXPECT_EQ(m.status().liveSource, 1u);
}

TEST(StateMachineNode, LiveSourceKeepsAnimatingDuringTheCrossfade) {
  GraphBuilder b(threeChannels());
  const ParameterIndex go = b.addTrigger("go");
  Timeline ramp;
  ramp.name = "ramp";
  ramp.duration = 10.0f;
  ramp.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f}, {10.0f, 1.0f}});
  const uint32_t clip = b.addTimeline(ramp);
  StateMachineNode m;
  m.states = {{"talk", b.add(TimelineNode{.timeline = clip}), {}}, {"still", addPose(b, {0, 0, 1}), {}}};
  m.states[0].transitions.push_back({.to = "still", .duration = 2.0f, .conditions = {trigger(go)}});
  b.setRoot(b.add(std::move(m)));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  face.update(2.0f);  // ramp at 0.2
  face.setTrigger(go);
  face.update(1.0f);  // transition starts, w = 0; ramp keeps running: 0.3
  EXPECT_NEAR(face.weights()[0], 0.3f, 1e-5f);
  face.update(1.0f);  // w = 0.5, ramp 0.4
  EXPECT_NEAR(face.weights()[0], 0.5f * 0.4f, 1e-5f);
  EXPECT_NEAR(face.weights()[2], 0.5f, 1e-5f);
}

TEST(StateMachineNode, AnyStateSelfTransitionRestartsFromTheSnapshot) {
  GraphBuilder b(threeChannels());
  const ParameterIndex again = b.addTrigger("again");
  StateMachineNode m;
  m.states = {{"only", addPose(b, {0.5f, 0, 0}), {}}};
  m.anyState.push_back({.to = "only", .duration = 1.0f, .canTransitionToSelf = true, .conditions = {trigger(again)}});
  const NodeIndex machine = b.add(std::move(m));
  b.setRoot(machine);
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  face.setTrigger(again);
  face.update(0.1f);
  EXPECT_TRUE(face.stateMachineStatus(machine)->fromSnapshot);
  EXPECT_FLOAT_EQ(face.weights()[0], 0.5f);
}

TEST(StateMachineNode, InterruptingAnOvershootStartsFromTheDisplayedWeight) {
  // A back-ease curve carries the blend past the destination (weight > 1,
  // displayed as 1); the interruption must start from 1, not from the overshoot.
  GraphBuilder b(threeChannels());
  const ParameterIndex up = b.addTrigger("up"), down = b.addTrigger("down");
  StateMachineNode m;
  m.states = {{"low", addPose(b, {0, 0, 0}), {}}, {"high", addPose(b, {1, 0, 0}), {}}};
  const EasingCurve backEase = EasingCurve::bezier({0.3f, 0.0f, 0.6f, 1.6f}).value();
  m.states[0].transitions.push_back({.to = "high", .duration = 1.0f, .curve = backEase, .conditions = {trigger(up)}});
  m.states[1].transitions.push_back({.to = "low", .duration = 1.0f, .conditions = {trigger(down)}});
  b.setRoot(b.add(std::move(m)));
  GraphInstance face = instantiate(buildGraph(b));
  face.update(0.0f);
  face.setTrigger(up);
  face.update(0.0f);
  face.update(0.8f);
  ASSERT_GT(backEase(0.8f), 1.05f);  // the blend overshoots inside the graph here
  EXPECT_FLOAT_EQ(face.weights()[0], 1.0f);
  face.setTrigger(down);
  face.update(0.0f);
  EXPECT_FLOAT_EQ(face.weights()[0], 1.0f);
  face.update(0.25f);
  EXPECT_NEAR(face.weights()[0], 0.75f, 1e-5f);
}

TEST(StateMachineNodeValidity, ProblemsNameTheTransitionAndField) {
  auto error = [](auto edit) {
    GraphBuilder b(threeChannels());
    const ParameterIndex t = b.addTrigger("t");
    b.addFloat("f");
    StateMachineNode m;
    m.states = {{"A", addPose(b, {0, 0, 0}), {}}, {"B", addPose(b, {1, 0, 0}), {}}};
    m.states[1].transitions.push_back({.to = "A", .duration = 0.5f, .conditions = {trigger(t)}});
    edit(m);
    b.setRoot(b.add(std::move(m)));
    return buildError(b);
  };
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].transitions[0].duration = 0.0f; })
                .find("node 2 (stateMachine)/states/1/transitions/0/duration: must be a finite number > 0"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].transitions[0].to = "Q"; })
                .find("/states/1/transitions/0/to: no state named 'Q'"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].transitions[0].conditions.clear(); })
                .find("/states/1/transitions/0: has neither conditions nor an exit time"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].transitions[0].conditions[0].parameter = 1; })
                .find("/states/1/transitions/0/conditions/0/parameter: parameter 'f' is a float, expected a trigger"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].name = "A"; }).find("/states/1/name: state 'A' is declared twice"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.defaultState = "Z"; }).find("/defaultState: no state named 'Z'"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.states[1].transitions[0].canTransitionToSelf = true; })
                .find("canTransitionToSelf: only any-state transitions"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) { m.anyState.push_back({.to = "A", .exitTime = -1.0f}); })
                .find("/anyState/0/exitTime: must be a finite number >= 0"),
            std::string::npos);
  EXPECT_NE(error([](StateMachineNode& m) {
              m.states[1].transitions[0].curve = EasingCurve::keyed({Keyframe{0, 0, 0, 0, KeyInterpolation::Step}, Keyframe{1, 1}}).value();
            }).find("/curve: the curve jumps"),
            std::string::npos);
}
