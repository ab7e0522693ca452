#include "facial/runtime/graph/graph_instance.h"

#include <atomic>
#include <cmath>
#include <random>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "importers/vrm_import.h"
#include "facial/runtime/json/json_document.h"
#include "tests/common/allocation_counter.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;
using namespace graph_test;

namespace {

// Every node type in one tree over the action units:
// blink(additive(stateMachine{bilinear, controlMap, freeformMap, blend(timeline, pose)}, timeline)).
struct EveryNode {
  EveryNode() {
    const uint32_t n = static_cast<uint32_t>(actionUnits().size());
    GraphBuilder b(ChannelSet::actionUnits());
    go = b.addTrigger("go");
    back = b.addTrigger("back");
    x = b.addFloat("x");
    y = b.addFloat("y");
    expression = b.addFloat("expression");
    auto pose = [&](float w, uint32_t channel) {
      std::vector<float> weights(n, 0.0f);
      weights[channel % n] = w;
      return addPose(b, weights);
    };
    Timeline clip;
    clip.name = "talk";
    clip.duration = 1.0f;
    clip.loop = LoopMode::Loop;
    clip.addTrack("AU26_JawDrop", std::vector<Keyframe>{{0, 0, 0, 0, KeyInterpolation::Cosine}, {0.5f, 0.7f}, {1, 0}});
    clip.addTrack("AU25_LipsPart", std::vector<Keyframe>{{0, 0.2f, 0, 1, KeyInterpolation::Hermite}, {1, 0.3f}});
    const uint32_t talk = b.addTimeline(clip);
    const uint32_t talk2 = b.addTimeline([&] { Timeline t = clip; t.name = "talk2"; return t; }());

    BilinearNode bilinear{.shape1 = {pose(0.5f, 1), pose(0.7f, 2), pose(0.2f, 3)},
                          .shape2 = {pose(0.1f, 4), pose(0.9f, 5), pose(0.4f, 6)},
                          .shape = FloatInput::fixed(0.3f), .expression = expression, .duration = 0.4f};
    ControlMapNode map{.neutral = pose(0, 0), .e1 = pose(1, 7), .e2 = pose(1, 8), .e3 = pose(1, 9), .e4 = pose(1, 10),
                       .x = FloatInput::bound(x), .y = FloatInput::bound(y)};
    FreeformMapNode freeform{.neutral = pose(0, 0), .x = FloatInput::bound(y), .y = FloatInput::bound(x)};
    for (int i = 0; i < 6; ++i)
      freeform.poles.push_back({{std::cos(i * 1.047f), std::sin(i * 1.047f)}, pose(1, 11 + i)});
    const NodeIndex mixed = b.add(BlendNode{.a = b.add(TimelineNode{.timeline = talk}), .b = pose(0.6f, 12),
                                            .factor = FloatInput::bound(x), .curve = EasingCurve::smoothstep()});
    StateMachineNode machine;
    machine.states = {{"bilinear", b.add(bilinear), {}}, {"map", b.add(map), {}}, {"freeform", b.add(freeform), {}},
                      {"mixed", mixed, {}}};
    for (int s = 0; s < 4; ++s) {
      machine.states[s].transitions.push_back(
          {.to = machine.states[(s + 1) % 4].name, .duration = 0.3f, .curve = EasingCurve::cosine(), .conditions = {{go}}});
      machine.states[s].transitions.push_back({.to = machine.states[(s + 3) % 4].name, .duration = 0.5f, .exitTime = 3.0f});
    }
    machine.anyState.push_back({.to = "bilinear", .duration = 0.2f, .conditions = {{back}}});
    const NodeIndex layered = b.add(AdditiveNode{.base = b.add(std::move(machine)), .layer = b.add(TimelineNode{.timeline = talk2}),
                                                 .mask = {.region = FaceRegion::Lower}});
    b.setRoot(b.add(BlinkNode{.input = layered}));
    graph = buildGraph(b);
  }
  // Drives every parameter from a seeded stream; returns the weights of each frame.
  std::vector<float> run(GraphInstance& face, uint32_t seed, int frames) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> trace;
    for (int f = 0; f < frames; ++f) {
      if (u(rng) < 0.05f) face.setTrigger(go);
      if (u(rng) < 0.01f) face.setTrigger(back);
      face.setFloat(x, 2 * u(rng) - 1);
      face.setFloat(y, 2 * u(rng) - 1);
      if (u(rng) < 0.02f) face.setFloat(expression, std::floor(3 * u(rng)));
      face.update(0.002f + 0.03f * u(rng));
      trace.insert(trace.end(), face.weights().begin(), face.weights().end());
    }
    return trace;
  }
  SharedGraphDefinition graph;
  ParameterIndex go = 0, back = 0, x = 0, y = 0, expression = 0;
};

}  // namespace

TEST(GraphInstance, UpdateNeverAllocates) {
  EveryNode rig;
  GraphInstance face = instantiate(rig.graph, 3);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const uint64_t before = testing_support::allocationCount();
  for (int f = 0; f < 20000; ++f) {
    if (u(rng) < 0.05f) face.setTrigger(rig.go);
    if (u(rng) < 0.01f) face.setTrigger(rig.back);
    face.setFloat(rig.x, 2 * u(rng) - 1);
    face.setFloat(rig.expression, std::floor(3 * u(rng) * (u(rng) < 0.02f)));
    face.update(0.001f + 0.04f * u(rng));
  }
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
  // The hook does count: creating an instance allocates.
  const uint64_t beforeCreate = testing_support::allocationCount();
  GraphInstance other = instantiate(rig.graph);
  EXPECT_GT(testing_support::allocationCount() - beforeCreate, 0u);
}

TEST(GraphInstance, SameInputsAndStepsGiveTheSameWeightsBitForBit) {
  EveryNode rig;
  GraphInstance a = instantiate(rig.graph, 9), b = instantiate(rig.graph, 9);
  EXPECT_EQ(rig.run(a, 5, 3000), rig.run(b, 5, 3000));
  a.reset();
  GraphInstance c = instantiate(rig.graph, 9);
  EXPECT_EQ(rig.run(a, 6, 1000), rig.run(c, 6, 1000));  // reset == fresh
}

TEST(GraphInstance, CharactersSharingADefinitionKeepTheirOwnState) {
  EveryNode rig;
  GraphInstance a = instantiate(rig.graph, 1), b = instantiate(rig.graph, 1);
  rig.run(a, 1, 500);
  const std::vector<float> fresh = rig.run(b, 2, 10);
  GraphInstance c = instantiate(rig.graph, 1);
  EXPECT_EQ(fresh, rig.run(c, 2, 10));
}

TEST(GraphInstanceValidity, ParameterWritesCheckIndexTypeAndValue) {
  EveryNode rig;
  GraphInstance face = instantiate(rig.graph);
  EXPECT_TRUE(face.setFloat(rig.x, 0.5f));
  EXPECT_FALSE(face.setFloat(rig.x, NAN));
  EXPECT_FALSE(face.setFloat(rig.x, INFINITY));
  EXPECT_EQ(face.parameters()[rig.x], 0.5f);
  EXPECT_FALSE(face.setFloat(rig.go, 1.0f));     // a trigger
  EXPECT_FALSE(face.setBool(rig.x, true));       // a float
  EXPECT_FALSE(face.setTrigger(rig.x));
  EXPECT_FALSE(face.setFloat(999, 1.0f));
  EXPECT_TRUE(face.setTrigger(rig.go));
  EXPECT_TRUE(face.resetTrigger(rig.go));
  EXPECT_EQ(face.parameters()[rig.go], 0.0f);
  EXPECT_FALSE(face.stateMachineStatus(rig.graph->root()).has_value());  // the root is the blink node
}

TEST(GraphInstanceValidity, BadTimeStepsChangeNothing) {
  EveryNode rig;
  GraphInstance face = instantiate(rig.graph);
  ASSERT_TRUE(face.update(0.1f));
  const std::vector<float> before(face.weights().begin(), face.weights().end());
  EXPECT_FALSE(face.update(-0.01f));
  EXPECT_FALSE(face.update(NAN));
  EXPECT_FALSE(face.update(INFINITY));
  EXPECT_EQ(before, std::vector<float>(face.weights().begin(), face.weights().end()));
  EXPECT_FALSE(GraphInstance::create(nullptr).ok());
}

// The per-frame work of a VRM face's material binds (what app::FaceMaterials
// runs every frame for every instance): resolve the expression weights, move
// the materials. Nothing allocates once sized.
TEST(GraphInstance, VrmMaterialBindsPerFrameNeverAllocate) {
  auto document = parseJsonText(R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],
    "materials": [{"name": "skin"}, {"name": "eyes"}],
    "meshes": [{"primitives": [{"attributes": {}, "targets": [{}]}]}],
    "extensions": {"VRMC_vrm": {"specVersion": "1.0", "expressions": {"preset": {
      "happy": {"morphTargetBinds": [{"node": 0, "index": 0, "weight": 1}],
                "materialColorBinds": [{"material": 0, "type": "color", "targetValue": [1, 0, 0, 1]}]},
      "blink": {"textureTransformBinds": [{"material": 1, "scale": [1, 0.5], "offset": [0, 0.5]}]},
      "angry": {"overrideBlink": "block",
                "materialColorBinds": [{"material": 0, "type": "emissionColor", "targetValue": [0.2, 0, 0, 1]}]}}}}}})",
                               "alloc.vrm");
  ASSERT_TRUE(document) << document.error().message;
  auto set = importers::importVrmExpressions(*document, "alloc.vrm");
  ASSERT_TRUE(set) << set.error().message;
  std::vector<float> weights(set->expressions.size()), effective(weights.size());
  std::vector<VrmMaterialState> rest(set->materialCount), moved(set->materialCount);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const uint64_t before = testing_support::allocationCount();
  for (int f = 0; f < 5000; ++f) {
    for (float& w : weights) w = u(rng);
    ASSERT_TRUE(set->effectiveWeights(weights, effective));
    ASSERT_TRUE(set->applyMaterials(effective, rest, moved));
  }
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
}
