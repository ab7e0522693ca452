// Property: whatever triggers arrive, at whatever time steps, no weight pops.
//
// Bound. With states that hold still poses, a frame's output is
//   P = (1 - c(tau/d)) S + c(tau/d) D
// (S the live source or the snapshot taken at an interruption, D the
// destination). Between two frames of one blend P moves by
// (c(tau2/d) - c(tau1/d)) (D - S), and |D - S| <= 1 because weights live in
// [0,1], so |dP| <= maxSlope(c) * dt / d. A frame that starts a blend shows
// S = what was on screen (tau = 0), and a frame that ends one at tau >= d
// shows D = c(1)... both inside the same bound. Hence for every frame
//   |dP| <= dt * max over transitions of maxSlope(curve) / duration.
// Layers add their own rates (blink_node.h): see the tour test below.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/rig/expression_library.h"
#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

struct RandomMachine {
  SharedGraphDefinition graph;
  std::vector<ParameterIndex> triggers;
  ParameterIndex level = 0;
  double maxRate = 0.0;  // max over transitions of maxSlope / duration, per second
};

// Seven still poses wired by trigger, float, exit-time and any-state
// transitions with random durations and curves; some not interruptible.
RandomMachine randomMachine(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const uint32_t n = static_cast<uint32_t>(actionUnits().size());
  const std::vector<EasingCurve> curves = {EasingCurve::linear(), EasingCurve::cosine(), EasingCurve::smoothstep(),
                                           EasingCurve::bezier({0.42f, 0.0f, 0.58f, 1.0f}).value(),
                                           EasingCurve::bezier({0.3f, -0.4f, 0.6f, 1.5f}).value(),
                                           EasingCurve::keyed({Keyframe{0, 0, 0, 0, KeyInterpolation::Cosine},
                                                               Keyframe{0.4f, 0.7f}, Keyframe{1, 1}}).value()};
  RandomMachine out;
  GraphBuilder b(ChannelSet::actionUnits());
  for (int t = 0; t < 4; ++t) out.triggers.push_back(b.addTrigger("t" + std::to_string(t)));
  out.level = b.addFloat("level");
  StateMachineNode machine;
  for (int s = 0; s < 7; ++s) {
    std::vector<float> pose(n);
    for (float& w : pose) w = u(rng) < 0.5f ? u(rng) : (u(rng) < 0.5f ? 1.0f : 0.0f);
    machine.states.push_back({"s" + std::to_string(s), b.add(PoseNode{.weights = pose}), {}});
  }
  auto transition = [&](int to) {
    Transition t{.to = "s" + std::to_string(to), .duration = 0.05f + 0.95f * u(rng),
                 .curve = curves[static_cast<size_t>(u(rng) * curves.size()) % curves.size()]};
    t.interruptible = u(rng) < 0.8f;
    t.priority = static_cast<int>(u(rng) * 3);
    out.maxRate = std::max(out.maxRate, t.curve.maxSlope() / t.duration);
    return t;
  };
  for (int s = 0; s < 7; ++s) {
    for (int k = 0; k < 3; ++k) {
      Transition t = transition(static_cast<int>(u(rng) * 7) % 7);
      if (t.to == machine.states[s].name) t.to = "s" + std::to_string((s + 1) % 7);
      const float kind = u(rng);
      if (kind < 0.5f) t.conditions.push_back({out.triggers[k]});
      else if (kind < 0.75f) t.conditions.push_back({out.level, ConditionOp::Greater, u(rng)});
      else t.exitTime = 2.0f * u(rng);
      machine.states[s].transitions.push_back(std::move(t));
    }
  }
  for (int k = 0; k < 2; ++k) {
    Transition t = transition(static_cast<int>(u(rng) * 7) % 7);
    t.canTransitionToSelf = u(rng) < 0.5f;
    t.conditions.push_back({out.triggers[3 - k]});
    machine.anyState.push_back(std::move(t));
  }
  b.setRoot(b.add(std::move(machine)));
  out.graph = b.build().value();
  return out;
}

}  // namespace

TEST(StateMachineProperty, RandomTriggersAtRandomStepsNeverPop) {
  for (uint32_t seed = 1; seed <= 400; ++seed) {
    const RandomMachine m = randomMachine(seed);
    GraphInstance face = instantiate(m.graph);
    std::mt19937 rng(seed * 7919u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    face.update(0.0f);
    std::vector<float> previous(face.weights().begin(), face.weights().end());
    for (int frame = 0; frame < 1500; ++frame) {
      for (ParameterIndex t : m.triggers)
        if (u(rng) < 0.04f) face.setTrigger(t);
      if (u(rng) < 0.02f) face.setFloat(m.level, u(rng));
      const float dt = u(rng) < 0.05f ? 0.2f * u(rng) : 0.001f + 0.04f * u(rng);
      ASSERT_TRUE(face.update(dt));
      const float bound = static_cast<float>(m.maxRate) * dt + 1e-5f;
      for (size_t c = 0; c < previous.size(); ++c) {
        const float w = face.weights()[c];
        ASSERT_TRUE(std::isfinite(w) && w >= 0.0f && w <= 1.0f) << "seed " << seed << " frame " << frame;
        ASSERT_LE(std::abs(w - previous[c]), bound)
            << "seed " << seed << " frame " << frame << " channel " << actionUnits()[c].name << " dt " << dt;
        previous[c] = w;
      }
    }
  }
}

TEST(StateMachineProperty, TheTourNeverPopsWhateverTheViewerClicks) {
  // Tour = blink(additive(stateMachine, talk) ) with talk held at 0. The
  // emotion machine's blends move weights and the override lanes at most
  // r = (pi/2) / 0.6 s per second (cosine, shortest duration). On the blink
  // channels out = in + (1 - in) b amp, amp = (1 - smoothstep(w5)) (1 - block)
  // (1 - blend), so |d out| <= |d in| + |d b| + |d amp| with
  // |d amp| <= 1.5/(wideFull - wideStart) |d w5| + |d block| + |d blend| = (3 + 1 + 1) r dt
  // and |d b| <= blinkRate dt: blink channels move at most (6 r + blinkRate) dt.
  auto library = ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json");
  ASSERT_TRUE(library.ok()) << library.error().message;
  auto graph = loadGraph(testing_support::sourceDir() / "data" / "graphs" / "tour.json", {presetLookup(*library)});
  ASSERT_TRUE(graph.ok()) << graph.error().message;
  const BlinkNode& blink = *(*graph)->nodeAs<BlinkNode>((*graph)->root());
  const float r = static_cast<float>(EasingCurve::cosine().maxSlope()) / 0.6f;
  std::vector<ParameterIndex> triggers;
  for (std::string_view e : {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"})
    triggers.push_back(*(*graph)->findParameter(e));
  const ParameterIndex autoplay = *(*graph)->findParameter("autoplay");
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    GraphInstance face = instantiate(*graph, seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    face.update(0.0f);
    std::vector<float> previous(face.weights().begin(), face.weights().end());
    for (int frame = 0; frame < 3000; ++frame) {
      if (u(rng) < 0.03f) face.setTrigger(triggers[static_cast<size_t>(u(rng) * 7) % 7]);
      if (u(rng) < 0.01f) face.setBool(autoplay, u(rng) < 0.5f);
      const float dt = 0.002f + 0.04f * u(rng);
      ASSERT_TRUE(face.update(dt));
      for (size_t c = 0; c < previous.size(); ++c) {
        const bool isBlink = actionUnits()[c].facsNumber == 45;
        const float bound = (isBlink ? 6.0f * r + blink.maxRate() : r) * dt + 1e-5f;
        const float w = face.weights()[c];
        ASSERT_TRUE(std::isfinite(w) && w >= 0.0f && w <= 1.0f);
        ASSERT_LE(std::abs(w - previous[c]), bound) << "seed " << seed << " frame " << frame << " " << actionUnits()[c].name;
        previous[c] = w;
      }
    }
  }
}
